// Sweep mode of the integration labs (euler, midpoint): every integrator over
// a ladder of step sizes, one CSV row per run. See docs/sweep.md.
//   <lab> --scene S --sweep FILE.csv [--integrators a,b] [--dts list] [--repeats R]
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "wb/run.h"

namespace wb {

// The top-level scene keys a sweep lab accepts beyond the base ones: "exact".
const std::vector<std::string>& sweep_scene_keys();

// A scene's closed-form motion, from its "exact" key (docs/scenes.md).
struct ExactSolution {
  enum Kind { kNone, kOscillator, kKepler } kind = kNone;
  Vec2 center = Vec2::Zero();                 // the spring's anchor or the attractor's centre (m)
  double w = 0;                               // oscillator: sqrt(k/m) (rad/s)
  double GM = 0;                              // kepler: attractor strength (m^3/s^2)
  Vec2 x0 = Vec2::Zero(), v0 = Vec2::Zero();  // the particle's initial state
  // The particle's position and velocity at time t.
  void at(double t, Vec2& x, Vec2& v) const;
};

// Reads and checks the scene's "exact" key (kind kNone when it is absent).
// Throws InputError naming the key and what the scene must look like.
ExactSolution read_exact(const Scene& scene);

// The default step sizes for a scene step dt: dt * 2^k for k = 3, 2, ..., -6.
std::vector<double> default_dt_ladder(double dt);

// The reference step of an "rk4" reference: the smallest swept dt / 16.
constexpr double kReferenceRefinement = 16.0;

struct SweepOptions {
  std::string csv;                       // output file (written atomically)
  std::vector<std::string> integrators;  // empty: every integrator of the lab
  std::vector<double> dts;               // empty: default_dt_ladder(dt)
  std::optional<double> dt;              // --dt: the ladder's base (else the scene's dt)
  std::optional<double> t_end;           // --t-end (else the scene's t_end)
  int repeats = 3;                       // wall_s = fastest of this many timed loops
  bool progress = true;                  // one line per run on stderr
  // Printed as "<exe>: warning: ..." once every option and integrator is
  // accepted, before the first run, with the integrators' own (Integrator::check).
  std::string exe = "sweep";
  std::vector<std::string> warnings;
};

// What the sweep wrote, for the summary line.
struct SweepResult {
  std::vector<SweepRow> rows;
};

// Runs the sweep and writes the CSV
//   scene,integrator,dt,steps,force_evals,wall_s,error,energy_error,reference,status
// Throws InputError for bad options or scene keys.
SweepResult run_sweep(const LabInfo& info, const Scene& scene, const World& world,
                      const SweepOptions& opt);

}  // namespace wb
