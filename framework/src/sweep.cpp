// Sweep mode: integrators x step sizes -> one CSV row per run (docs/sweep.md).
#include "wb/sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>

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

constexpr double kInf = std::numeric_limits<double>::infinity();

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
    if (!(x.allFinite() && v.allFinite())) break;
  }
  return x;
}

}  // namespace

SweepResult run_sweep(const LabInfo& info, const Scene& scene, const World& world,
                      const SweepOptions& opt) {
  // Which integrators, which step sizes, to what time (the contract's one plan).
  std::vector<std::string> names;
  for (const Integrator& it : info.integrators) names.push_back(it.name);
  const SweepPlan plan = plan_sweep(names, opt.integrators, opt.dts, opt.dt, opt.t_end, scene.dt,
                                    scene.t_end, scene.file, opt.repeats);
  const std::vector<double>& dts = plan.dts;
  const ExactSolution exact = read_exact(scene);
  const double h_ref = *std::min_element(dts.begin(), dts.end()) / kReferenceRefinement;
  const std::string ladder = opt.dts.empty()
                                 ? (opt.dt ? std::string("--dt") : scene.file + ": dt")
                                 : std::string("--dts");
  if (exact.kind == ExactSolution::kNone) {
    for (std::size_t d = 0; d < dts.size(); ++d) {
      const double n = std::round(double(plan.steps[d]) * dts[d] / h_ref);
      if (!(n <= double(kMaxSteps))) {
        throw InputError(ladder + ": the rk4 reference at the smallest dt / " +
                         num(kReferenceRefinement) + " = " + num(h_ref) + " takes " + num(n) +
                         " steps to t = " + num(double(plan.steps[d]) * dts[d]) +
                         ", expected at most " + std::to_string(kMaxSteps) +
                         " (use a larger smallest step, a shorter t_end or an \"exact\" scene)");
      }
    }
  }

  // Every integrator against the scene before the first run.
  std::vector<std::string> warnings = opt.warnings;
  for (std::size_t i : plan.integrators) {
    const Integrator& integ = info.integrators[i];
    if (!integ.check) continue;
    const std::string w = integ.check(integ, world.dynamics());
    if (!w.empty()) warnings.push_back(w);
  }

  // Opened now, so that an unwritable path fails before the runs.
  AtomicFile file(opt.csv);
  for (const auto& w : warnings) std::cerr << opt.exe << ": warning: " << w << "\n";

  // The reference: the exact motion, or RK4 at the smallest dt / 16 (cached
  // per end time: a dt that does not divide T ends at round(T/dt) dt).
  const std::string reference = exact.kind == ExactSolution::kNone ? "rk4" : "exact";
  std::map<double, Mat2X> rk4_cache;
  auto reference_positions = [&](double t) -> Mat2X {
    if (exact.kind != ExactSolution::kNone) {
      Vec2 x, v;
      exact.at(t, x, v);
      return x;
    }
    auto it = rk4_cache.find(t);
    if (it != rk4_cache.end()) return it->second;
    const long n = std::max(1L, long(std::llround(t / h_ref)));
    if (opt.progress) {
      std::cerr << "sweep: reference rk4 to t = " << t << " in " << n << " steps\n";
    }
    Mat2X x = rk4_positions(scene, world, t / double(n), n);
    if (!x.allFinite()) {
      std::cerr << "sweep: warning: the rk4 reference diverged at h = " << t / double(n)
                << ": errors against it are written as nan\n";
    }
    return rk4_cache.emplace(t, x).first->second;
  };

  SweepResult result;
  const std::size_t total = plan.integrators.size() * dts.size();
  const Energy e0 = world.energy(scene.x, scene.v);
  const double scale = relative_energy_scale(e0);
  // The run contract's rule for a diverged run (docs/run-contract.md).
  const double blowup_scale =
      energy_scale(e0.kinetic, e0.potential, particle_work_scale(scene, world));
  Scratch s;
  s.resize(scene.n());
  const Dynamics& dyn = world.dynamics();
  for (std::size_t i : plan.integrators) {
    const Integrator* integ = &info.integrators[i];
    for (std::size_t d = 0; d < dts.size(); ++d) {
      SweepRow row;
      row.integrator = i;
      row.dt = dts[d];
      row.steps = plan.steps[d];
      row.reference = reference;
      if (opt.progress) {
        std::cerr << "sweep: " << integ->name << " dt=" << num(row.dt) << " ("
                  << result.rows.size() + 1 << "/" << total << ")\n";
      }

      // Untimed run: divergence and the largest energy error over the run.
      Mat2X x = scene.x, v = scene.v;
      dyn.reset_evals();
      for (long k = 0; k < row.steps; ++k) {
        integ->step(dyn, row.dt, x, v, s);
        world.after_step(row.dt, x, v);
        const bool finite = x.allFinite() && v.allFinite();
        const double E = finite ? world.energy(x, v).total() : NAN;
        if (!divergence(finite, E, blowup_scale, k + 1).empty()) {
          row.diverged = true;
          break;
        }
        row.energy_error = std::max(row.energy_error, std::abs(E - e0.total()) / scale);
      }
      row.diverged =
          row.diverged || !unconverged_divergence(row.steps, dyn.unconverged()).empty();
      if (row.steps > 0 && x == scene.x && v == scene.v) {
        std::cerr << "sweep: warning: " << integ->name << " at dt=" << num(row.dt)
                  << ": the state never changed in " << row.steps
                  << " steps: its error measures the scene, not the method (is the step "
                     "still a stub?)\n";
      }
      if (row.diverged) {
        row.error = row.energy_error = kInf;
      } else {
        const Mat2X ref = reference_positions(double(row.steps) * row.dt);
        row.error = (x - ref).colwise().norm().maxCoeff();
        if (!ref.allFinite()) row.error = std::numeric_limits<double>::quiet_NaN();
      }

      // Timed runs: the pure step loop, fastest of opt.repeats.
      row.wall_s = kInf;
      for (int r = 0; r < opt.repeats; ++r) {
        x = scene.x;
        v = scene.v;
        dyn.reset_evals();
        const auto start = std::chrono::steady_clock::now();
        for (long k = 0; k < row.steps; ++k) {
          integ->step(dyn, row.dt, x, v, s);
          world.after_step(row.dt, x, v);
        }
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        row.wall_s = std::min(row.wall_s, wall);
        row.force_evals = dyn.evals();
      }
      result.rows.push_back(row);
    }
  }

  // The CSV, written atomically.
  file.write(sweep_table(scene.name, names, result.rows));
  file.commit();
  return result;
}

}  // namespace wb
