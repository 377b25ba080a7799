// The budget a run measures while it runs (docs/scenes.md, "Cost"; docs/run-contract.md):
// the process's CPU time and resident memory, watched from its flags on, whatever the
// cost model estimated. A run that reaches --max-time or --max-memory stops there:
// exit status 2 and one line naming the phase that took the time (or was growing the
// memory), the step it reached and the total it was heading for, its output
// temporaries removed. The static estimate (wb/cost.h) still refuses a run before its
// first step and answers --estimate; this is the wall behind it.
//
// The code says which phase it is in (PhaseScope: a store, no clock read), the step
// loops count their steps (step_done()), and a watchdog samples the clocks every few
// milliseconds: on POSIX a thread of its own (framework/src/budget_clock.cpp, the only
// file that calls the platform); where there are no threads (WB_BUDGET_THREAD 0,
// WebAssembly without pthreads), step_done() and every PhaseScope count down to a read
// of std::clock() instead.
#pragma once
#include <atomic>
#include <string>

// WB_BUDGET_THREAD: 1 where the watchdog is a thread of its own (POSIX, emscripten with
// pthreads), 0 where a build has no threads (emscripten without -pthread: the live
// pages' WebAssembly). Without one, the run's own thread reads the clock at its step
// boundaries (step_done) and at its phase boundaries (PhaseScope), about every 10 ms of
// CPU: a stretch of work with neither (one long solve) is stopped only at its end.
#ifndef WB_BUDGET_THREAD
#if defined(__unix__) && (!defined(__EMSCRIPTEN__) || defined(__EMSCRIPTEN_PTHREADS__))
#define WB_BUDGET_THREAD 1
#else
#define WB_BUDGET_THREAD 0
#endif
#endif

namespace wb::budget {

// What the run is doing, for the message that stops it. Keep kPhaseCount last.
enum Phase : int {
  kLoad,       // reading and checking the scene file
  kPrepare,    // building the run: the world, the initial checks, a solver's analysis
  kStep,       // the integrator's own arithmetic
  kForces,     // evaluating the force terms
  kEnergy,     // the divergence rule's energy and the bookkeeping of each step
  kPairs,      // the broad and narrow phases: candidate pairs and contacts found
  kContacts,   // the contact impulses (collisions, rigid bodies)
  kHinges,     // the rigid lab's hinges
  kNewton,     // the implicit lab's Newton step: assembly and direct solves
  kCg,         // conjugate gradient iterations
  kOutput,     // writing the trace, the stats or the sweep table
  kReference,  // a sweep's rk4 reference run
  kPhaseCount
};

// The phase the running code is in: written by it (relaxed stores, plain moves on
// common hardware), sampled by the watchdog.
extern std::atomic<int> g_phase;
inline void set_phase(Phase p) { g_phase.store(p, std::memory_order_relaxed); }

#if WB_BUDGET_THREAD
inline void phase_boundary() {}  // the watchdog thread looks by itself
#else
// poll_clock()'s countdown, where no ticker runs (LONG_MAX while nothing is watched).
extern long g_countdown;
void poll_clock();
// A phase begins or ends: one decrement of the poll's countdown, the clock read when it
// reaches 0 (poll_clock). Inline: a call costs more than the decrement, and a force
// evaluation has two boundaries (docs/benchmarks.md, "Live pages").
inline void phase_boundary() {
  if (--g_countdown <= 0) poll_clock();
}
#endif

// Sets the phase for its lifetime, then restores the one before (phases nest:
// the forces inside a step, the CG iterations inside a Newton step).
class PhaseScope {
 public:
  explicit PhaseScope(Phase p) : saved_(g_phase.load(std::memory_order_relaxed)) {
    set_phase(p);
    phase_boundary();
  }
  ~PhaseScope() {
    g_phase.store(saved_, std::memory_order_relaxed);
    phase_boundary();
  }
  PhaseScope(const PhaseScope&) = delete;
  PhaseScope& operator=(const PhaseScope&) = delete;

 private:
  int saved_;
};

// The limits, from --max-time and --max-memory (wb/cost.h's defaults).
struct Limits {
  double seconds = 0;  // CPU seconds of the whole process
  double bytes = 0;    // resident memory (B)
};

// Starts watching this process: from now on, reaching a limit stops it (exit 2, one
// line "<exe>: error: <file>: stopped ..."). `exe` and `file` name the run in that
// line. Nothing is measured before this (the flags' parsing). Call once per process;
// a second call only changes the names and limits.
void start(const Limits& limits, const std::string& exe, const std::string& file);

// The plan's size once it is known: `total_steps` steps of the step loops in all
// (a sweep: every run, repeats and reference included), for the projected total.
void plan(double total_steps);
// The step loops have started (the load and the checks are behind): their CPU time
// is what the projection scales.
void loop_started();

// The run is over (its summary is next): the watchdog stops looking, so that a run which
// finished is never stopped while it prints and exits.
void finish();

// One step done (any run of the plan): a relaxed store and a decrement, cheap enough
// for every step. Where no ticker runs (WebAssembly) it also reads the clock every so
// many steps and phase boundaries (poll_clock), about every 10 ms of CPU.
void step_done();
void poll_clock();

// The line for an allocation that failed (std::bad_alloc, caught by guarded_main:
// exit 2): where the run was, and that --max-memory stops a run before that.
std::string out_of_memory_text();

// Is the watch running (start() called and a ticker or poll() active)? For tests.
bool watching();

// CPU seconds and resident bytes of this process now (0 when the platform cannot say).
double cpu_seconds();
double resident_bytes();

// The phase's name as the stopping line says it ("the broad phase's candidate pairs").
const char* phase_name(int p);

}  // namespace wb::budget
