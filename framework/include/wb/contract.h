// The run contract's parts that do not depend on a lab's state type
// (docs/run-contract.md): the one rule that says a run diverged, the step loop
// that applies it, the summary line, the --help paragraphs on integrators and
// sweeps, and the sweep's ladder and table. The particle labs (wb::Mat2X
// state, framework/src/run.cpp, sweep.cpp) and the rigid lab (rigid::Body
// state, framework/drivers/rigid/rigid_run.cpp) both call these: one contract,
// one implementation, whatever the state.
#pragma once
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "wb/input.h"

namespace wb {

// The most steps one run takes (--steps, or round(T/H)); docs/run-contract.md.
constexpr long kMaxSteps = 100'000'000;

// ---- Diverged (docs/run-contract.md, "Diverged"): one rule for every lab.

// |E| past this many times the run's initial energy scale is a blow-up (the
// figures' log scale has drawn such runs as blown up since the first labs):
// no scene of the workbook gains a factor of 1000 on purpose, and explicit
// methods outside their stability region pass it within tens of steps.
constexpr double kBlowUpFactor = 1000.0;
// A run whose implicit solver did not converge on more than this share of its
// steps is diverged even if it stayed finite: its states are not solutions
// of the method's equations (the stiff rope with a failing CG: 161 of 200).
constexpr double kMaxUnconvergedShare = 0.5;

// The energy scale E_s a run's |E| is compared with: the largest of |E0|,
// K0 + |V0| (a total near 0 by the choice of the potential's zero) and work0,
// the work the initial forces would do across the scene (sum of m|a| times
// the scene size, docs/run-contract.md): a scene that starts at rest with
// zero potential (a rope laid out straight) still has a scale.
double energy_scale(double kinetic0, double potential0, double work0);

// Has the state after a step diverged: a state that is not finite, an energy that
// is not finite, or |E| > kBlowUpFactor times `scale`. The rule alone, for a loop
// that asks it after every step and wants divergence()'s sentence only when it has
// (building an empty one cost 6 % of the cheapest live step in WebAssembly).
inline bool diverges(bool state_finite, double energy, double scale) {
  return !state_finite || !std::isfinite(energy) || std::abs(energy) > kBlowUpFactor * scale;
}

// Why the state after `step` has diverged (diverges()), or "" while it has not.
std::string divergence(bool state_finite, double energy, double scale, long step);

// Why a finished run has diverged by its solver, or "": more than
// kMaxUnconvergedShare of `steps` did not converge.
std::string unconverged_divergence(long steps, long unconverged);

// ---- The step loop.

struct StepHooks {
  std::function<void()> step;                       // one step of the state
  std::function<bool()> finite;                     // is the state finite?
  std::function<double()> energy;                   // its total energy (J)
  std::function<void(long step, double t)> record;  // write it to the trace and stats
};

struct LoopResult {
  long steps = 0;      // steps taken
  std::string reason;  // why the run diverged ("" when it did not)
  double wall_s = 0;   // the loop's wall time, writing included
  double cpu_s = 0;    // the process's CPU time in the loop: what other work on the machine
                       // does not inflate (the report's cost figure uses it)
};

// Takes up to `steps` steps of size dt, records step 0, every `every`-th step
// and the last one; stops at the first step whose state diverged (recorded).
LoopResult run_steps(long steps, long every, double dt, double scale, const StepHooks& hooks);

// ---- The summary line (docs/run-contract.md, "The summary line").

struct Summary {
  std::string diverged;  // why the run diverged, "" when it is ok
  long steps = 0;
  double t = 0;
  long force_evals = 0;
  double wall_s = 0, cpu_s = 0;
  double energy0 = 0, energy = 0;
  std::vector<double> momentum0, momentum;  // 2 or 3 components
  long unconverged = -1;                    // < 0: the lab has no solver to report
  ordered_json extra;                       // lab keys after the momenta (object or null)
  std::vector<std::string> warnings;        // what stubs do; non-empty: "stub": true too
};

// The summary line's JSON object, keys in the documented order. The status
// is "diverged" when `diverged` says why, and whenever a number the line
// prints is not finite: "ok" with "energy": null cannot happen.
ordered_json summary_json(const Summary& s);

// The summary line printed last on stdout: the object as JSON on one line (bytes
// that are not UTF-8, from a file name, become U+FFFD rather than an exception).
void print_summary(const ordered_json& j);

// Every line a lab executable writes on stderr, and the only function that writes
// one: "<exe>: <kind>: <text>", kind "error", "warning" or "internal error", the
// text as one_line() makes it (control bytes, line breaks and invalid UTF-8 escaped,
// so a file name or a key from outside cannot split it). Diagnostics are warnings
// or nothing.
void say(const std::string& exe, const char* kind, const std::string& text);

// main()'s body: runs `body`; bad input (InputError) prints one line and
// returns 2, any other exception returns 1 ("internal error").
int guarded_main(const std::string& exe, const std::function<int()>& body);

// ---- --help paragraphs.

// One line of the integrator list.
struct IntegratorLine {
  std::string name, description;
  int order = 1, evals_per_step = 1;
};
std::string integrators_help(const std::vector<IntegratorLine>& list);

// The sweep paragraph: `what` says what the errors are measured against.
std::string sweep_help(const std::string& what);

// The --help paragraph on the cost model's flags (--max-time, --max-memory, --estimate).
std::string budget_help();

// ---- Sweep mode's ladder and table (docs/sweep.md).

struct SweepPlan {
  std::vector<std::size_t> integrators;  // indices into the lab's list
  std::vector<double> dts;
  std::vector<long> steps;  // round(T / dt) each
  double t_end = 0;
  std::string ladder;  // who chose the step sizes, for messages: "--dts", "--dt" or "<file>: dt"
};

// Which integrators (--integrators, else all), which step sizes (--dts, else
// dt*2^k for k = 3..-6 from --dt or the scene's dt) and to what time (--t-end,
// else the scene's t_end); InputError naming the flag or scene key.
SweepPlan plan_sweep(const std::vector<std::string>& names,
                     const std::vector<std::string>& wanted, const std::vector<double>& dts,
                     std::optional<double> dt, std::optional<double> t_end,
                     std::optional<double> scene_dt, std::optional<double> scene_t_end,
                     const std::string& scene_file, int repeats);

// What one run of a sweep measured.
struct SweepRow {
  std::size_t integrator = 0;
  double dt = 0;
  long steps = 0, force_evals = 0;
  double wall_s = 0, error = 0, energy_error = 0;
  std::string reference;  // "exact" or "rk4"
  bool diverged = false;
};

// The sweep's CSV header: scene,integrator,dt,steps,force_evals,wall_s,error,
// energy_error,reference,status
std::string sweep_columns();

// The sweep's CSV text: the header (unless `header` is false), then one row per run.
std::string sweep_table(const std::string& scene, const std::vector<std::string>& names,
                        const std::vector<SweepRow>& rows, bool header = true);

// The sweep's summary line: status ok, the file, how many runs and how many diverged.
ordered_json sweep_summary(const std::string& csv, const std::vector<SweepRow>& rows);

// ---- Sweep mode's loop, whatever the lab's state (docs/sweep.md).

// What the loop needs of a lab's state: the particle labs' (framework/src/particle_lab.cpp)
// and the rigid lab's (framework/drivers/rigid/rigid_run.cpp).
struct SweepHooks {
  std::function<void()> reset;  // back to the initial state
  // `n` steps of size h with integrator `i` (a loop of its own: the timed runs
  // measure the step, not a call per step)
  std::function<void(std::size_t i, double h, long n)> steps;
  std::function<bool()> finite;           // is the state finite?
  std::function<double()> energy;         // its total energy (J)
  std::function<bool()> moved;            // has the state changed since reset()?
  std::function<long()> evals;            // force evaluations since reset()
  std::function<long()> unconverged;      // steps whose implicit solve failed since reset()
  std::function<double(double t)> error;  // the run's error, at its end (time t)
  double energy0 = 0;                     // the initial total energy (J)
  double energy_scale = 1;                // what makes an energy error relative
  double blowup_scale = 0;                // the divergence rule's E_s (energy_scale())
  std::string reference;                  // "exact" or "rk4"
  std::string unmoved;                    // ends the warning of a run whose state never changed
};

// Runs every (integrator, step size) of the plan: an untimed run (divergence, the
// largest energy error, the final error), then `repeats` timed runs of the pure step
// loop (wall_s: the fastest). A run whose state never changed warns ("<exe>: warning:").
std::vector<SweepRow> sweep_rows(const SweepPlan& plan, const std::vector<std::string>& names,
                                 const SweepHooks& h, const std::string& exe, int repeats);

}  // namespace wb
