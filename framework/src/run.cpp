// The run contract: flags, the step loop, the trace, the summary line.
#include "wb/run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>

#include <unistd.h>

#include "wb/cli.h"
#include "wb/output.h"
#include "wb/sweep.h"

namespace wb {

std::vector<std::string> default_scenes(const std::string& lab) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(scenes_dir() + "/" + lab, ec)) {
    if (e.path().extension() == ".json") {
      out.push_back("scenes/" + lab + "/" + e.path().filename().string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string num(double x) {
  std::string s;
  append_number(s, x);
  return s;
}

const Integrator& find_integrator(const LabInfo& info, const std::string& name,
                                  const std::string& where) {
  return find_named(info.integrators, name, where);
}

namespace {

// Rows of the trace: t,id,x,y,vx,vy per particle.
void append_trace_rows(std::string& buf, double t, const Mat2X& x, const Mat2X& v) {
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    append_number(buf, t);
    buf += ',';
    append_int(buf, i);
    for (double q : {x(0, i), x(1, i), v(0, i), v(1, i)}) {
      buf += ',';
      append_number(buf, q);
    }
    buf += '\n';
  }
}

void append_stats_row(std::string& buf, long step, double t, const Energy& e, const Vec2& p,
                      long evals) {
  append_int(buf, step);
  for (double q : {t, e.total(), e.kinetic, e.potential, p.x(), p.y()}) {
    buf += ',';
    append_number(buf, q);
  }
  buf += ',';
  append_int(buf, evals);
  buf += '\n';
}

}  // namespace

std::int64_t parse_whole(const std::string& flag, const std::string& text, std::int64_t min,
                         std::int64_t max) {
  // The scene files' reader and rule (wb::read_number, docs/scenes.md "Whole numbers"):
  // JSON's grammar (no sign but "-", no base prefix, so 010 is refused as JSON refuses
  // it), exactly a whole number (1e3 and 5.0 are; 0.5 is not), no silent clamping.
  const std::string expected =
      "a whole number from " + std::to_string(min) + " to " + std::to_string(max);
  const NumberText t = read_number(text);
  std::int64_t v = 0;
  if (!whole_in(t, min, max, v)) {
    throw InputError(flag + ": got \"" + text + "\", expected " + expected +
                     (t.valid ? ""
                              : " (written as in JSON: digits, no blanks, no \"+\", no "
                                "leading zeros, no hex)"));
  }
  return v;
}

namespace {

// The scene size S: the extent of the initial positions or their largest distance
// from the origin, 1 m when both are 0 (tools/wbplot/recipes.py's length_scale, the
// report's scene size).
double scene_size(const Scene& scene) {
  double S = 0;
  if (scene.n() > 0) {
    const Vec2 lo = scene.x.rowwise().minCoeff(), hi = scene.x.rowwise().maxCoeff();
    S = std::max((hi - lo).norm(), scene.x.colwise().norm().maxCoeff());
  }
  return std::isfinite(S) && S > 0 ? S : 1.0;
}

// The terms' force bounds on every particle (Force::bound), summed.
VecX force_bounds(const Scene& scene, const std::vector<const Force*>& terms) {
  VecX bound = VecX::Zero(scene.n());
  for (const Force* t : terms) t->bound(scene.x, scene.v, scene.m, bound);
  return bound;
}

}  // namespace

void check_initial_state(const Scene& scene, const World& world) {
  const Mat2X& x = scene.x;
  const Mat2X& v = scene.v;
  const std::vector<const Force*> terms = world.terms();
  // Forces: every term's bound, summed particle by particle, and over the mass.
  VecX bound = VecX::Zero(scene.n());
  for (const Force* t : terms) {
    t->bound(x, v, scene.m, bound);
    const Eigen::Array<double, Eigen::Dynamic, 1> a = bound.array() / scene.m.array();
    if (bound.allFinite() && a.allFinite()) continue;
    Eigen::Index i = 0;  // the first particle whose bound is not finite
    while (std::isfinite(bound[i]) && std::isfinite(a[i])) ++i;
    throw InputError(scene.file + ": " + t->blame(x, v) +
                     ": initial state: the force on particle " + std::to_string(i) +
                     " (this term and those before it) is bounded by " + num(bound[i]) +
                     " N, its acceleration by " + num(a[i]) +
                     " m/s^2, expected finite forces and accelerations f/m (a force constant, "
                     "position, velocity or mass so large that they overflow)");
  }
  // The divergence rule's energy scale has a floor, the work the initial forces would do
  // across the scene (particle_work_scale): bounded by sum |f_i| times S with the bounds
  // above, it must be finite, or the rule would compare every step with a scale of 0.
  const double S = scene_size(scene);
  if (!std::isfinite(bound.sum() * S)) {
    Eigen::Index i = 0;
    bound.maxCoeff(&i);
    throw InputError(scene.file + ": " + particle_key(scene, i) +
                     ": initial state: the work the initial forces would do across the scene, "
                     "sum of |f| times the scene's size " +
                     num(S) +
                     " m (the divergence "
                     "rule's energy scale, docs/run-contract.md), overflows (the largest force, "
                     "on particle " +
                     std::to_string(i) + ", is bounded by " + num(bound[i]) +
                     " N), expected masses, forces and positions whose product is finite");
  }
  // Energy: kinetic, then each term's potential; the momentum.
  const Energy e = world.energy(x, v);
  const Vec2 p = momentum(v, scene.m);
  if (std::isfinite(e.kinetic) && std::isfinite(e.potential) && std::isfinite(e.total()) &&
      p.allFinite()) {
    return;
  }
  std::string where = "particles and emitters";  // the kinetic energy or the momentum
  double V = 0;
  for (const Force* t : terms) {
    V += t->potential(x, scene.m);
    if (!std::isfinite(V) || !std::isfinite(e.kinetic + V)) {
      where = t->blame(x, v);
      break;
    }
  }
  throw InputError(scene.file + ": " + where + ": initial state: kinetic energy " +
                   num(e.kinetic) + ", potential energy " + num(e.potential) + ", momentum [" +
                   num(p.x()) + ", " + num(p.y()) +
                   "], expected finite values (a position, velocity, mass or force constant "
                   "is so large that they overflow)");
}

double particle_work_scale(const Scene& scene, const World& world) {
  const double S = scene_size(scene);
  const Dynamics& dyn = world.dynamics();
  Mat2X a(2, scene.n());
  dyn.acceleration(scene.x, scene.v, a);
  dyn.reset_evals();
  const double work = (a.colwise().norm().transpose().array() * scene.m.array()).sum() * S;
  if (std::isfinite(work)) return work;
  // Forces beyond their bounds (a lab's function gone wrong): the bounds' work, finite
  // by check_initial_state, rather than a scale of 0.
  return force_bounds(scene, world.terms()).sum() * S;
}

RunResult simulate(const Scene& scene, const World& world, const RunOptions& opt) {
  RunResult r;
  Mat2X x = scene.x, v = scene.v;
  const Dynamics& dyn = world.dynamics();
  r.energy0 = world.energy(x, v);
  r.momentum0 = momentum(v, scene.m);
  const double scale =
      energy_scale(r.energy0.kinetic, r.energy0.potential, particle_work_scale(scene, world));
  dyn.reset_evals();
  Scratch scratch;
  scratch.resize(x.cols());

  CsvFile no_trace, no_stats;
  CsvFile& trace = opt.trace ? *opt.trace : no_trace;
  CsvFile& stats = opt.stats ? *opt.stats : no_stats;
  // Did any step change the state, by the integrator or by the collision phase (discs
  // overlapping at rest are moved by the phase alone)? Compared with the scene's own
  // state, so that the check copies nothing.
  bool moved = false;
  StepHooks hooks;
  hooks.step = [&] {
    opt.integrator->step(dyn, opt.dt, x, v, scratch);
    world.after_step(opt.dt, x, v);
    if (!moved) moved = x != scene.x || v != scene.v;
  };
  // The divergence rule's bookkeeping: one pass where the world can (World::checked_energy).
  double checked = 0;
  hooks.finite = [&] {
    bool finite = false;
    checked = world.checked_energy(x, v, finite);
    return finite;
  };
  hooks.energy = [&] { return checked; };
  hooks.record = [&](long step, double t) {
    if (trace) {
      append_trace_rows(trace.rows(), t, x, v);
      trace.flush_if_large();
    }
    if (stats) {
      append_stats_row(stats.rows(), step, t, world.energy(x, v), momentum(v, scene.m),
                       dyn.evals());
      stats.flush_if_large();
    }
  };
  const LoopResult loop = run_steps(opt.steps, opt.every, opt.dt, scale, hooks);
  const long k = loop.steps;
  r.wall_s = loop.wall_s;
  r.cpu_s = loop.cpu_s;
  r.steps = k;
  r.t = double(k) * opt.dt;
  r.force_evals = dyn.evals();
  r.unconverged = dyn.unconverged();
  r.energy = world.energy(x, v);
  r.diverged = loop.reason;
  if (r.diverged.empty()) r.diverged = unconverged_divergence(k, r.unconverged);
  // A stub looks like a perfect run (energy conserved exactly): say so.
  if (k > 0 && opt.integrator->evals_per_step > 0 && r.force_evals == 0) {
    r.warnings.push_back("the integrator \"" + opt.integrator->name +
                         "\" evaluated no forces in " + std::to_string(k) +
                         " steps: is its step function written yet?");
  }
  // Nothing moved: a stub when something should have (a particle with a velocity, or a
  // force term declared); a scene at rest with no forces stays at rest by right.
  const bool could_move = !scene.v.isZero(0) || !world.terms().empty();
  if (k > 0 && !moved && scene.n() > 0 && could_move) {
    r.warnings.push_back("the state never changed in " + std::to_string(k) +
                         " steps (no step moved a particle or changed a velocity): is the "
                         "step, or a force, still a stub?");
  }
  for (const std::string& w : world.warnings(x, v)) r.warnings.push_back(w);
  r.momentum = momentum(v, scene.m);
  trace.commit();
  stats.commit();
  r.x = std::move(x);
  r.v = std::move(v);
  return r;
}

Summary summary_of(const RunResult& r) {
  Summary s;
  s.diverged = r.diverged;
  s.steps = r.steps;
  s.t = r.t;
  s.force_evals = r.force_evals;
  s.wall_s = r.wall_s;
  s.cpu_s = r.cpu_s;
  s.energy0 = r.energy0.total();
  s.energy = r.energy.total();
  s.momentum0 = {r.momentum0.x(), r.momentum0.y()};
  s.momentum = {r.momentum.x(), r.momentum.y()};
  s.unconverged = r.unconverged;
  s.warnings = r.warnings;
  return s;
}

}  // namespace wb
