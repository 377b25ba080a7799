// The run contract shared by every particle lab executable:
//   <lab> --scene FILE.json [--integrator NAME] [--dt H] [--steps N | --t-end T]
//         [--out trace.csv] [--stats stats.csv] [--every K] [--seed S]
// See docs/run-contract.md.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "wb/dynamics.h"
#include "wb/scene.h"
#include "wb/scene_forces.h"

namespace wb {

struct LabInfo {
  std::string lab;                      // "forces"
  std::string side;                     // "student" or "solution"
  std::string summary;                  // one line for --help
  std::vector<Integrator> integrators;  // the first is the default
  bool sweep = false;                   // offers --sweep (integration labs)
};

// What one simulation produced: the summary line's fields.
struct RunResult {
  bool diverged = false;
  long steps = 0;  // steps taken
  double t = 0;
  long force_evals = 0;
  double wall_s = 0;
  Energy energy0, energy;
  Vec2 momentum0 = Vec2::Zero(), momentum = Vec2::Zero();
  Mat2X x, v;  // final state
};

struct RunOptions {
  const Integrator* integrator = nullptr;
  double dt = 0;
  long steps = 0;
  long every = 1;
  std::string out;    // trace CSV, empty for none
  std::string stats;  // energy/momentum CSV, empty for none
};

// Runs one scene from its initial state. Throws InputError for bad input.
RunResult simulate(const Scene& scene, const ForceList& forces, const RunOptions& opt);

// The integrator called `name`, or InputError naming `where` and the known names.
const Integrator& find_integrator(const LabInfo& info, const std::string& name,
                                  const std::string& where);

// main() of a particle lab: parses flags, runs, prints the summary; returns
// the exit status (0 ok or diverged, 2 bad input, 1 internal error).
int run_particle_lab(int argc, char** argv, const LabInfo& info);

// The default scenes shipped for a lab (files under scenes/<lab>/), sorted.
std::vector<std::string> default_scenes(const std::string& lab);
std::string scenes_dir();

}  // namespace wb
