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

// A CSV field: quoted only when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// The scale that makes an energy error relative: |E0|, unless E0 is tiny
// against its parts (energy near zero by the choice of the potential's zero),
// then K0 + |V0|; 1 (an absolute error) when the scene has no energy at all.
double energy_scale(const Energy& e0) {
  const double parts = std::abs(e0.kinetic) + std::abs(e0.potential);
  if (std::abs(e0.total()) > 1e-6 * parts) return std::abs(e0.total());
  return parts > 0.0 ? parts : 1.0;
}

struct Row {
  const Integrator* integrator;
  double dt = 0;
  long steps = 0;
  long force_evals = 0;
  double wall_s = 0;
  double error = 0, energy_error = 0;
  bool diverged = false;
};

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
  // Which integrators, which step sizes, to what time.
  std::vector<const Integrator*> integrators;
  if (opt.integrators.empty()) {
    for (const Integrator& it : info.integrators) integrators.push_back(&it);
  } else {
    for (const std::string& name : opt.integrators) {
      integrators.push_back(&find_integrator(info, name, "--integrators"));
    }
  }
  if (!(opt.repeats >= 1)) {
    throw InputError("--repeats: got " + std::to_string(opt.repeats) +
                     ", expected a whole number >= 1");
  }
  const double T = opt.t_end ? *opt.t_end : scene.t_end.value_or(-1.0);
  if (!(T > 0.0 && std::isfinite(T))) {
    throw InputError(opt.t_end ? "--t-end: got " + num(T) + ", expected a number > 0 for a sweep"
                               : scene.file + ": t_end: " +
                                     (scene.t_end ? "got " + num(T) : std::string("missing")) +
                                     ", expected a number > 0 for a sweep (or pass --t-end)");
  }
  std::vector<double> dts = opt.dts;
  if (dts.empty()) {
    if (!opt.dt && !scene.dt) {
      throw InputError(scene.file +
                       ": dt: missing, expected a number > 0 (or pass --dt or --dts)");
    }
    dts = default_dt_ladder(opt.dt ? *opt.dt : *scene.dt);
  }
  // Who chose the step sizes, for the messages below.
  const std::string ladder = opt.dts.empty()
                                 ? (opt.dt ? std::string("--dt") : scene.file + ": dt")
                                 : std::string("--dts");
  std::vector<long> steps;
  for (double dt : dts) {
    if (!(std::isfinite(dt) && dt > 0.0)) {
      throw InputError("--dts: got " + num(dt) + ", expected step sizes > 0");
    }
    const double n = std::round(T / dt);
    if (!(n >= 1.0 && n <= double(kMaxSteps))) {
      throw InputError(ladder + ": step " + num(dt) + " gives round(T/dt) = " + num(n) +
                       " steps for T = " + num(T) + ", expected 1 to " +
                       std::to_string(kMaxSteps));
    }
    steps.push_back(long(n));
  }
  const ExactSolution exact = read_exact(scene);
  const double h_ref = *std::min_element(dts.begin(), dts.end()) / kReferenceRefinement;
  if (exact.kind == ExactSolution::kNone) {
    for (std::size_t d = 0; d < dts.size(); ++d) {
      const double n = std::round(double(steps[d]) * dts[d] / h_ref);
      if (!(n <= double(kMaxSteps))) {
        throw InputError(ladder + ": the rk4 reference at the smallest dt / " +
                         num(kReferenceRefinement) + " = " + num(h_ref) + " takes " + num(n) +
                         " steps to t = " + num(double(steps[d]) * dts[d]) +
                         ", expected at most " + std::to_string(kMaxSteps) +
                         " (use a larger smallest step, a shorter t_end or an \"exact\" scene)");
      }
    }
  }

  // Every integrator against the scene before the first run.
  std::vector<std::string> warnings = opt.warnings;
  for (const Integrator* integ : integrators) {
    if (!integ->check) continue;
    const std::string w = integ->check(*integ, world.dynamics());
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

  std::vector<Row> rows;
  const std::size_t total = integrators.size() * dts.size();
  const Energy e0 = world.energy(scene.x, scene.v);
  const double scale = energy_scale(e0);
  Scratch s;
  s.resize(scene.n());
  for (const Integrator* integ : integrators) {
    for (std::size_t d = 0; d < dts.size(); ++d) {
      Row row;
      row.integrator = integ;
      row.dt = dts[d];
      row.steps = steps[d];
      if (opt.progress) {
        std::cerr << "sweep: " << integ->name << " dt=" << num(row.dt) << " (" << rows.size() + 1
                  << "/" << total << ")\n";
      }
      const Dynamics& dyn = world.dynamics();

      // Untimed run: divergence and the largest energy error over the run.
      Mat2X x = scene.x, v = scene.v;
      for (long k = 0; k < row.steps; ++k) {
        integ->step(dyn, row.dt, x, v, s);
        world.after_step(row.dt, x, v);
        if (!(x.allFinite() && v.allFinite())) {
          row.diverged = true;
          break;
        }
        const double de = std::abs(world.energy(x, v).total() - e0.total()) / scale;
        row.energy_error = std::max(row.energy_error, de);
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
      rows.push_back(row);
    }
  }

  // The CSV, written atomically.
  std::string out =
      "scene,integrator,dt,steps,force_evals,wall_s,error,energy_error,reference,status\n";
  SweepResult result;
  for (const Row& row : rows) {
    out += csv_field(scene.name) + ',' + csv_field(row.integrator->name) + ',';
    append_number(out, row.dt);
    out += ',';
    append_int(out, row.steps);
    out += ',';
    append_int(out, row.force_evals);
    for (double q : {row.wall_s, row.error, row.energy_error}) {
      out += ',';
      append_number(out, q);
    }
    out += ',' + reference + ',' + (row.diverged ? "diverged" : "ok") + '\n';
    ++result.runs;
    result.diverged += row.diverged ? 1 : 0;
  }
  file.write(out);
  file.commit();
  return result;
}

}  // namespace wb
