// The cost model (docs/scenes.md, "Cost"): before anything is built, a run (or a
// sweep, all its runs together) estimates its CPU time and memory term by term from
// the scene's numbers and the flags. Above the budget (--max-time, --max-memory) it
// is refused in one line naming the largest term and the flag that allows it; above
// the warning levels it warns with the estimate. Work whose amount depends on the
// state (candidate pairs, Newton and CG iterations) is counted while the run does it
// (WorkMeter): a step that does more than kOverrunFactor times its estimate stops
// the run with exit status 2. The core names no lab: each lab's glue adds its terms.
#pragma once
#include <string>
#include <vector>

#include "wb/input.h"

namespace wb {

// ---- The budget (flags --max-time SECONDS, --max-memory MIB).

// A run estimated above this much CPU time (at its iteration caps) is refused: an
// hour is past any scene of the workbook (the longest default scene takes 10 s)
// and is what a mistyped dt or count costs.
constexpr double kDefaultMaxSeconds = 3600.0;
// The memory budget: a student laptop, a Gradescope container (2 GiB of address space).
constexpr double kDefaultMaxBytes = 2.0 * 1024 * 1024 * 1024;
// Warned above this much CPU time (typical, not at the caps), or above this share
// of the memory budget: a minute is longer than any default scene.
constexpr double kWarnSeconds = 60.0;
constexpr double kWarnMemoryShare = 0.5;
// A step that counts more than this many times its estimated work of one kind
// (WorkMeter) stops the run: Newton's typical 4 iterations against its default cap
// of 20 stay below it, a tolerance it cannot meet with 1000 iterations does not.
constexpr double kOverrunFactor = 10.0;

struct Budget {
  double seconds = kDefaultMaxSeconds;
  double bytes = kDefaultMaxBytes;
};

// ---- Terms and estimates.

// One kind of work: what is counted, with its numbers ("forces[1] (newton): 2000
// particles, 1999000 pairs x 40002 evaluations"), the scene key or flag that sets
// it, and what it costs.
struct CostTerm {
  std::string what;
  std::string key;
  double seconds = 0;      // typical CPU time (s)
  double cap_seconds = 0;  // at its iteration caps (>= seconds)
  double bytes = 0;        // memory it holds at its peak (B)
};

class Estimate {
 public:
  // A term of `units` of work at `seconds_per_unit`, holding `bytes`; `cap_units`
  // (>= units) where the work stops on a test (an iteration cap), else the same.
  void add(const std::string& what, const std::string& key, double units, double seconds_per_unit,
           double bytes = 0, double cap_units = -1);
  // Every term of `e` repeated `times` (steps, runs), `how` appended to its text;
  // its memory counted once, or not at all without `hold` (runs that follow
  // one another: only the largest holds its memory at the peak).
  void add_times(const Estimate& e, double times, const std::string& how, bool hold = true);
  const std::vector<CostTerm>& terms() const { return terms_; }
  double seconds() const;
  double cap_seconds() const;
  double bytes() const;

 private:
  std::vector<CostTerm> terms_;
};

// What a lab's glue estimates for one integrator on a scene, before anything of the
// run is built: what a run builds and computes once (the World, the initial checks),
// one step (time; the memory it holds while it runs) and one written step of the
// trace and stats.
struct StepCost {
  Estimate once, step, record;
};

// Rates shared by every lab (measured with the solution on an idle machine,
// docs/scenes.md "Cost"): a process's start (reading the scene's first bytes, the
// libraries) and its resident base, a byte of scene file parsed, and a trace row.
constexpr double kStartSeconds = 3.0e-3;
constexpr double kBaseBytes = 32e6;
constexpr double kSecondsPerFileByte = 35e-9;
// A scene file's document in memory: about 50 bytes per byte of a list of small
// objects (450 000 force terms in 14.9 MB held 736 MiB once parsed, issue 45).
constexpr double kBytesPerFileByte = 50;
constexpr double kSecondsPerTraceRow = 250e-9;

// The estimate as words: "about 3 minutes of CPU (at most 20 minutes) and 1.2 GiB".
std::string describe_estimate(const Estimate& e);
// A duration or a size as words: "4.2 s", "3.1 hours"; "310 MiB".
std::string seconds_text(double s);
std::string bytes_text(double b);

// Refuses an estimate over the budget: InputError naming `file`, the estimate, its
// largest term and the flag value that allows it. Returns a warning sentence when
// it is above the warning levels, "" otherwise.
std::string judge(const Estimate& e, const Budget& b, const std::string& file);

// The estimate as the --estimate line prints it: status "estimate", seconds,
// cap_seconds, bytes, and every term.
ordered_json estimate_json(const Estimate& e);

// ---- The running check.

// One kind of work whose amount depends on the state, counted step by step against
// the model's estimate per step. count() throws InputError (exit 2, one line) when
// the step in progress passes kOverrunFactor times the estimate: checked before the
// work is done where it can be (the candidate pairs of a broad phase), so that a
// step cannot run out of memory first.
class WorkMeter {
 public:
  WorkMeter() = default;
  // `what` names the units ("candidate pairs"), `why` what bounds them in the
  // scene ("contact.iterations", "the particles' radii").
  WorkMeter(std::string file, std::string what, double per_step, std::string why);
  void next_step() {
    done_ = 0;
    ++step_;
  }
  // Would `units` more of this step's work pass the limit?
  bool over(double units) const { return done_ + units > limit(); }
  void count(double units);
  double limit() const { return kOverrunFactor * per_step_; }

 private:
  std::string file_, what_, why_;
  double per_step_ = 0;
  double done_ = 0;
  long step_ = 0;
};

}  // namespace wb
