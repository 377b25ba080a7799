// Sweep mode of the integration labs (euler, midpoint, implicit): every integrator
// over a ladder of step sizes, one CSV row per run. See docs/sweep.md. The loop,
// the plan and the table are the contract's (wb/contract.h); this is the
// particle labs' state and reference.
//   <lab> --scene S --sweep FILE.csv [--integrators a,b] [--dts list] [--repeats R]
#pragma once
#include <map>
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

// The "rk4" reference runs a sweep needs: for each distinct end time t of the
// plan's runs, the number of RK4 steps to t at about the smallest dt / 16.
struct ReferenceRun {
  double t = 0;
  long steps = 0;
};
std::vector<ReferenceRun> reference_runs(const SweepPlan& plan);

// Checks a sweep of a particle scene before it runs: at least one particle (its
// errors are particle positions), an "rk4" reference of at most kMaxSteps steps.
// InputError naming the scene or the flag that chose the ladder (`ladder`).
void check_sweep(const Scene& scene, const ExactSolution& exact, const SweepPlan& plan,
                 const std::string& ladder);

// The particle labs' state in sweep mode (wb::sweep_rows): the scene's initial
// state stepped by the lab's integrators and World; errors against `exact` or an
// RK4 run at the smallest dt / 16, cached per end time. Warnings ("<exe>:
// warning: ...") for a reference that diverged.
class ParticleSweep {
 public:
  ParticleSweep(const LabInfo& info, const Scene& scene, const World& world,
                const ExactSolution& exact, const SweepPlan& plan, std::string exe);
  SweepHooks hooks();

 private:
  Mat2X reference_positions(double t);
  const LabInfo& info_;
  const Scene& scene_;
  const World& world_;
  ExactSolution exact_;
  double h_ref_ = 0;
  std::string exe_;
  Mat2X x_, v_;
  Scratch scratch_;
  std::map<double, Mat2X> rk4_cache_;
};

}  // namespace wb
