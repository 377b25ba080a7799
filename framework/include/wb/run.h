// The run contract shared by every particle lab executable:
//   <lab> --scene FILE.json [--integrator NAME] [--dt H] [--steps N | --t-end T]
//         [--out trace.csv] [--stats stats.csv] [--every K] [--seed S]
// See docs/run-contract.md.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "wb/contract.h"
#include "wb/cost.h"
#include "wb/dynamics.h"
#include "wb/output.h"
#include "wb/paths.h"
#include "wb/scene.h"
#include "wb/world.h"

// The side this executable was linked for: "student" or "solution"
// (framework/src/side.cpp); a driver's WB_SIDE expands to a call of it.
const char* wb_build_side();

namespace wb {

struct LabInfo {
  std::string lab;                      // "forces"
  std::string side;                     // "student" or "solution"
  std::string summary;                  // one line for --help
  std::vector<Integrator> integrators;  // the first is the default
  bool sweep = false;                   // offers --sweep (integration labs)
  WorldFactory make_world;              // the lab's glue: a scene's physics
  // Optional: adds what a lab's scene generators declare (a rope's beads, a
  // cloth's grid) to a loaded scene, before make_world; throws InputError.
  std::function<void(Scene&)> expand_scene;
  std::vector<std::string> scene_keys;     // top-level scene keys the glue reads
  std::vector<std::string> help_sections;  // extra --help paragraphs (force types, keys)
  // The cost model's terms of the glue for one integrator on a scene (docs/scenes.md,
  // "Cost"): its forces, its after-step phase, its solver. Called before make_world:
  // it reads the scene's numbers only.
  std::function<void(const Scene&, const Integrator&, StepCost&)> step_cost;
};

// What one simulation produced: the summary line's fields.
struct RunResult {
  std::string diverged;  // why the run diverged (docs/run-contract.md), "" when it did not
  long steps = 0;        // steps taken
  double t = 0;
  long force_evals = 0;
  long unconverged = 0;  // steps whose implicit solve did not converge
  // the step loop's wall time and the process's CPU time in it (s)
  double wall_s = 0, cpu_s = 0;
  Energy energy0, energy;
  Vec2 momentum0 = Vec2::Zero(), momentum = Vec2::Zero();
  Mat2X x, v;  // final state
  // Plain-language warnings that the run did nothing a student may take for
  // success (a step that left the state unchanged, no force evaluated).
  std::vector<std::string> warnings;
};

struct RunOptions {
  const Integrator* integrator = nullptr;
  double dt = 0;
  long steps = 0;
  long every = 1;
  CsvFile* trace = nullptr;  // t,id,x,y,vx,vy, opened before the run (wb/lab.h); null: none
  CsvFile* stats = nullptr;  // step,t,energy,...; null: none
};

// A whole-number flag: a number in JSON's grammar that is exactly a whole number in
// [min, max] (wb::read_number, as a scene's whole numbers: 1e3 and 10.0 are 10^3 and
// 10), else InputError naming the flag, the text and the range (no clamping).
std::int64_t parse_whole(const std::string& flag, const std::string& text, std::int64_t min,
                         std::int64_t max);

// Refuses a scene whose initial forces, energy or momentum are not finite (finite
// input that overflows), naming the scene key that caused it (World::terms()) and
// the values. The forces are bounded with the terms' own bounds (Force::bound),
// never computed by a lab's functions: the skeleton refuses what the solution does.
void check_initial_state(const Scene& scene, const World& world);

// The work the initial forces would do across the scene, sum of m_i |a_i(0)|
// times the scene size (J): the floor of the run's energy scale (energy_scale).
double particle_work_scale(const Scene& scene, const World& world);

// Runs one scene from its initial state. Throws InputError for bad input.
RunResult simulate(const Scene& scene, const World& world, const RunOptions& opt);

// The integrator called `name`, or InputError naming `where` and the known names.
const Integrator& find_integrator(const LabInfo& info, const std::string& name,
                                  const std::string& where);

// A run's summary line (wb::Summary) from its result.
Summary summary_of(const RunResult& r);

// main() of a particle lab: the run contract's main (wb::run_lab) with the
// particle labs' scenes (framework/src/particle_lab.cpp); returns the exit status
// (0 ok or diverged, 2 bad input, 1 internal error).
int run_particle_lab(int argc, char** argv, const LabInfo& info);

// The default scenes shipped for a lab (files under scenes/<lab>/), sorted,
// as paths relative to the repository (scenes/<lab>/NAME.json).
std::vector<std::string> default_scenes(const std::string& lab);

// A number as the summary and messages print it (17 significant digits).
std::string num(double x);

}  // namespace wb
