// One main() for every lab executable, whatever its state type (docs/run-contract.md):
// the flags, the cost model, the outputs, the warnings, the run or the sweep, the
// summary line. A lab says how it presents itself (LabSpec) and what it does with a
// scene (LabScene); the particle labs' LabScene is framework/src/particle_lab.cpp, the
// rigid lab's framework/drivers/rigid/rigid_run.cpp. A second state type is a second
// small class, not a second main.
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "wb/cli.h"
#include "wb/contract.h"
#include "wb/cost.h"
#include "wb/output.h"

namespace wb {

// How an executable presents itself: its --help and the flags it offers.
struct LabSpec {
  std::string lab, side, summary;
  std::vector<IntegratorLine> integrators;   // the first is the default
  std::vector<std::string> help_sections;    // after the integrators (force types, scene keys)
  std::string trace_columns, stats_columns;  // the CSV headers of --out and --stats
  bool seed = false;                         // offers --seed
  bool sweep = false;                        // offers --sweep
  std::string sweep_scenes;  // what a sweep's scene must be ("on a torque-free scene"), or ""
  std::string sweep_errors;  // what the sweep's errors are measured against, for --help
  std::string exe() const { return lab + (side == "student" ? "" : "-" + side); }
};

// A run's outputs, opened (and so checked) before the run starts and before any warning.
struct RunFiles {
  RunFiles(const std::string& out, const std::string& trace_header, const std::string& stats_path,
           const std::string& stats_header)
      : trace(out, trace_header, "--out"), stats(stats_path, stats_header, "--stats") {}
  CsvFile trace, stats;  // either may be nothing (its flag not given)
};

// One run as the contract asks it of a lab.
struct RunRequest {
  std::size_t integrator = 0;  // index in the lab's list
  double dt = 0;
  long steps = 0, every = 1;
};

// A lab's scene once loaded and checked: what the contract needs of it.
class LabScene {
 public:
  virtual ~LabScene() = default;
  std::string exe;  // for messages (set by run_lab)
  std::string file, name;
  std::optional<double> dt, t_end;
  std::optional<std::string> integrator;

  // The cost model's terms of integrator i on this scene (docs/scenes.md, "Cost"),
  // from the scene's numbers: nothing of the run is built yet.
  virtual void cost(std::size_t integrator, StepCost& c) const = 0;
  // What a sweep adds besides its runs (a reference run).
  virtual void sweep_cost(const SweepPlan& /*plan*/, Estimate& /*e*/) const {}
  // The steps of that reference run, for the budget's projection (wb/budget.h).
  virtual double reference_steps(const SweepPlan& /*plan*/) const { return 0; }
  // Builds what the runs of these integrators need (a sweep's: `sweep` is its
  // plan, else null) and checks what it derives from the scene (initial forces,
  // energy, momenta; what an integrator or a sweep requires): InputError naming
  // the key. Returns warnings to print.
  virtual std::vector<std::string> prepare(const std::vector<std::size_t>& integrators,
                                           const SweepPlan* sweep) = 0;
  // One run from the initial state, its rows written to `files`.
  virtual Summary run(const RunRequest& r, RunFiles& files) = 0;
  // Sweep mode's state (after prepare(..., true)).
  virtual SweepHooks sweep_hooks() = 0;
};

// Reads and checks the scene the flags name (InputError).
using LabLoader = std::function<std::unique_ptr<LabScene>(const RunFlags&)>;

// main() of a lab: returns the exit status (0 ok or diverged, 2 bad input, 1 internal error).
int run_lab(int argc, char** argv, const LabSpec& spec, const LabLoader& load);

// The estimate of one run, or of a whole sweep, as run_lab forms it.
Estimate run_estimate(const LabScene& s, const RunRequest& r, bool outputs,
                      const std::string& scene_file);
Estimate sweep_estimate(const LabScene& s, const SweepPlan& plan, int repeats,
                        const std::string& scene_file);

}  // namespace wb
