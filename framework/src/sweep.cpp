// Sweep mode: integrators x step sizes -> one CSV row per run (docs/sweep.md).
#include "wb/sweep.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "wb/budget.h"
#include "wb/contract.h"
#include "wb/exact.h"
#include "wb/output.h"
#include "wb/rk4.h"

namespace wb {

const std::vector<std::string>& sweep_scene_keys() {
  static const std::vector<std::string> keys = {"exact"};
  return keys;
}

void ExactSolution::at(double t, Vec2& x, Vec2& v) const {
  if (kind == kOscillator) {
    oscillator_exact(center, w, x0, v0, t, x, v);
  } else {
    kepler_exact(center, GM, x0, v0, t, x, v);
  }
}

namespace {

// The closed form evaluated where sweeps evaluate it (t = 0, a quarter of the
// scene's time, t_end) must be finite: otherwise every error would be nan.
template <class Require>
void require_finite_motion(const ExactSolution& ex, const Scene& scene, const Require& require) {
  const double T = scene.t_end.value_or(0.0);
  for (double t : {0.0, 0.25 * T, T}) {
    Vec2 x, v;
    ex.at(t, x, v);
    require(x.allFinite() && v.allFinite(),
            "a closed-form motion that stays finite (at t = " + num(t) + " it is not)");
  }
}

}  // namespace

ExactSolution read_exact(const Scene& scene) {
  ExactSolution ex;
  JsonObject top(scene.file, scene.doc, "");
  if (!top.has("exact")) return ex;
  const std::string kind = top.string("exact");
  const json* value = &scene.doc.at("exact");
  if (kind != "oscillator" && kind != "kepler") {
    top.fail("exact", value, "one of: oscillator, kepler");
  }
  // Each check names what the scene must look like for this key.
  auto require = [&](bool ok, const std::string& what) {
    if (!ok) top.fail("exact", value, "a scene with " + what);
  };
  require(scene.n() == 1,
          "exactly one particle for \"" + kind + "\" (it has " + std::to_string(scene.n()) + ")");
  const json& forces = top.array_or_empty("forces");
  const std::string one_force = kind == "oscillator" ? "spring" : "attractor";
  require(forces.size() == 1, "exactly one force, of type \"" + one_force + "\", for \"" + kind +
                                  "\" (it has " + std::to_string(forces.size()) + ")");
  JsonObject f = top.element("forces", 0);
  require(f.string("type") == one_force, "exactly one force, of type \"" + one_force +
                                             "\", for \"" + kind + "\" (forces[0] has type \"" +
                                             f.string("type") + "\")");
  ex.x0 = scene.x.col(0);
  ex.v0 = scene.v.col(0);
  const double m = scene.m[0];

  if (kind == "oscillator") {
    ex.kind = ExactSolution::kOscillator;
    require(f.has("anchor"),
            "a spring to an \"anchor\" for \"oscillator\" (forces[0] joins two particles)");
    ex.center = f.vec2("anchor");
    const double rest = f.number_or("rest", (ex.x0 - ex.center).norm(), Range{0.0});
    require(rest == 0.0,
            "a spring of \"rest\": 0 for \"oscillator\" (rest is " + num(rest) + ")");
    require(f.number_or("damping", 0.0, Range{0.0}) == 0.0,
            "an undamped spring for \"oscillator\" (forces[0].damping is not 0)");
    const double k = f.number("k", Range{0.0});
    require(k > 0.0, "a spring of k > 0 for \"oscillator\"");
    ex.w = std::sqrt(k / m);
    require(std::isfinite(ex.w) && std::isfinite(1.0 / ex.w),
            "w = sqrt(k/m) finite and > 0 for \"oscillator\" (it is " + num(ex.w) + ")");
    require_finite_motion(ex, scene, require);
    return ex;
  }

  ex.kind = ExactSolution::kKepler;
  ex.center = f.vec2_or("center", Vec2::Zero());
  ex.GM = f.number("GM", Range{0.0});
  require(ex.GM > 0.0, "an attractor of GM > 0 for \"kepler\"");
  const Vec2 r0 = ex.x0 - ex.center;
  require(r0.norm() > 0.0, "the particle away from the attractor's centre for \"kepler\"");
  require(0.5 * ex.v0.squaredNorm() - ex.GM / r0.norm() < 0.0,
          "a bound orbit for \"kepler\" (1/2 |v|^2 - GM/r must be < 0: circular or elliptic)");
  require(cross(r0, ex.v0) != 0.0,
          "an orbit with angular momentum for \"kepler\" (the velocity is radial)");
  // The closed form's constants (kepler_exact): semi-major axis a, mean
  // motion n, period, sqrt(GM a) must not overflow or vanish.
  const double eps = 0.5 * ex.v0.squaredNorm() - ex.GM / r0.norm();
  const double a = -ex.GM / (2.0 * eps);
  const double n = std::sqrt(ex.GM / (a * a * a));
  const double period = 2.0 * M_PI / n;
  const double sqrt_gma = std::sqrt(ex.GM * a);
  const bool ok = std::isfinite(eps) && eps < 0.0 && std::isfinite(a) && a > 0.0 &&
                  std::isfinite(n) && n > 0.0 && std::isfinite(period) && period > 0.0 &&
                  std::isfinite(sqrt_gma) && sqrt_gma > 0.0;
  require(ok, "an orbit whose closed form is finite for \"kepler\" (semi-major axis " + num(a) +
                  ", mean motion " + num(n) + ": the numbers overflow)");
  require_finite_motion(ex, scene, require);
  return ex;
}

std::vector<double> default_dt_ladder(double dt) {
  std::vector<double> out;
  for (int k = 3; k >= -6; --k) out.push_back(std::ldexp(dt, k));  // exact powers of two
  return out;
}

namespace {

// The scale that makes an energy error relative: |E0|, unless E0 is tiny
// against its parts (energy near zero by the choice of the potential's zero),
// then K0 + |V0|; 1 (an absolute error) when the scene has no energy at all.
double relative_energy_scale(const Energy& e0) {
  const double parts = std::abs(e0.kinetic) + std::abs(e0.potential);
  if (std::abs(e0.total()) > 1e-6 * parts) return std::abs(e0.total());
  return parts > 0.0 ? parts : 1.0;
}

// Positions at time steps * h of an RK4 run, or non-finite if it diverged.
Mat2X rk4_positions(const Scene& scene, const World& world, double h, long steps) {
  const Dynamics& dyn = world.dynamics();
  Mat2X x = scene.x, v = scene.v;
  Scratch s;
  s.resize(x.cols());
  for (long k = 0; k < steps; ++k) {
    rk4_step(dyn, h, x, v, s);
    world.after_step(h, x, v);
    budget::step_done();
    if (!(x.allFinite() && v.allFinite())) break;
  }
  return x;
}

double smallest_dt(const SweepPlan& plan) {
  return *std::min_element(plan.dts.begin(), plan.dts.end());
}

}  // namespace

std::vector<ReferenceRun> reference_runs(const SweepPlan& plan) {
  const double h_ref = smallest_dt(plan) / kReferenceRefinement;
  std::vector<ReferenceRun> runs;
  for (std::size_t d = 0; d < plan.dts.size(); ++d) {
    const double t = double(plan.steps[d]) * plan.dts[d];
    bool seen = false;
    for (const ReferenceRun& r : runs) seen = seen || r.t == t;
    if (seen) continue;
    const double n = std::max(1.0, std::round(t / h_ref));
    runs.push_back({t, n <= double(kMaxSteps) ? long(n) : kMaxSteps + 1});
  }
  return runs;
}

void check_sweep(const Scene& scene, const ExactSolution& exact, const SweepPlan& plan,
                 const std::string& ladder) {
  if (scene.n() == 0) {
    throw InputError("--sweep: " + scene.file +
                     ": the scene has no particles, expected at least one (a sweep measures "
                     "the particles' position errors)");
  }
  if (exact.kind != ExactSolution::kNone) return;
  const double h_ref = smallest_dt(plan) / kReferenceRefinement;
  for (const ReferenceRun& r : reference_runs(plan)) {
    if (r.steps > kMaxSteps) {
      throw InputError(ladder + ": the rk4 reference at the smallest dt / " +
                       num(kReferenceRefinement) + " = " + num(h_ref) + " takes " +
                       num(std::round(r.t / h_ref)) + " steps to t = " + num(r.t) +
                       ", expected at most " + std::to_string(kMaxSteps) +
                       " (use a larger smallest step, a shorter t_end or an \"exact\" scene)");
    }
  }
}

ParticleSweep::ParticleSweep(const LabInfo& info, const Scene& scene, const World& world,
                             const ExactSolution& exact, const SweepPlan& plan, std::string exe)
    : info_(info),
      scene_(scene),
      world_(world),
      exact_(exact),
      h_ref_(smallest_dt(plan) / kReferenceRefinement),
      exe_(std::move(exe)) {
  scratch_.resize(scene.n());
}

Mat2X ParticleSweep::reference_positions(double t) {
  if (exact_.kind != ExactSolution::kNone) {
    Vec2 x, v;
    exact_.at(t, x, v);
    return x;
  }
  auto it = rk4_cache_.find(t);
  if (it != rk4_cache_.end()) return it->second;
  const long n = std::max(1L, long(std::llround(t / h_ref_)));
  Mat2X x = rk4_positions(scene_, world_, t / double(n), n);
  if (!x.allFinite()) {
    say(exe_, "warning",
        "the rk4 reference diverged at h = " + num(t / double(n)) +
            ": errors against it are written as nan");
  }
  return rk4_cache_.emplace(t, x).first->second;
}

SweepHooks ParticleSweep::hooks() {
  SweepHooks h;
  const Dynamics& dyn = world_.dynamics();
  const Energy e0 = world_.energy(scene_.x, scene_.v);
  h.reset = [this, &dyn] {
    x_ = scene_.x;
    v_ = scene_.v;
    dyn.reset_evals();
  };
  h.steps = [this, &dyn](std::size_t i, double dt, long n) {
    const Integrator& integ = info_.integrators[i];
    for (long k = 0; k < n; ++k) {
      integ.step(dyn, dt, x_, v_, scratch_);
      world_.after_step(dt, x_, v_);
      budget::step_done();
    }
  };
  h.finite = [this] { return x_.allFinite() && v_.allFinite(); };
  h.energy = [this] { return world_.energy(x_, v_).total(); };
  h.moved = [this] { return x_ != scene_.x || v_ != scene_.v; };
  h.evals = [&dyn] { return dyn.evals(); };
  h.unconverged = [&dyn] { return dyn.unconverged(); };
  h.error = [this](double t) {
    const Mat2X ref = reference_positions(t);
    if (!ref.allFinite()) return std::numeric_limits<double>::quiet_NaN();
    return (x_ - ref).colwise().norm().maxCoeff();
  };
  h.energy0 = e0.total();
  h.energy_scale = relative_energy_scale(e0);
  h.blowup_scale = energy_scale(e0.kinetic, e0.potential, particle_work_scale(scene_, world_));
  h.reference = exact_.kind == ExactSolution::kNone ? "rk4" : "exact";
  h.unmoved = "its error measures the scene, not the method (is the step still a stub?)";
  return h;
}

}  // namespace wb
