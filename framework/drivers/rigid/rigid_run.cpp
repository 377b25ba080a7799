// The rigid lab's scenes for the run contract's main (wb/lab.h; docs/run-contract.md,
// "The rigid lab"): the same main, flags, cost model, outputs, step loop, sweep loop
// and summary line as the particle labs; only the 3D state, its cost terms and its
// errors are this lab's. Sweep mode: work-precision on a torque-free body.
#include <algorithm>
#include <cmath>
#include <memory>

#include "rigid_world.h"
#include "wb/budget.h"
#include "wb/lab.h"
#include "wb/run.h"

namespace rigid {

namespace {

using wb::append_int;
using wb::append_number;
using wb::InputError;
using wb::num;
using wb::ordered_json;

std::vector<Body> initial_bodies(const Scene& scene) {
  std::vector<Body> bodies;
  for (const BodyDef& d : scene.bodies) bodies.push_back(d.body);
  return bodies;
}

bool finite(const std::vector<Body>& bodies) {
  for (const Body& b : bodies) {
    if (!(b.x.allFinite() && b.v.allFinite() && b.q.coeffs().allFinite() &&
          b.omega.allFinite())) {
      return false;
    }
  }
  return true;
}

void append_trace_rows(std::string& buf, double t, const std::vector<Body>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    append_number(buf, t);
    buf += ',';
    append_int(buf, long(i));
    for (double q : {b.x.x(), b.x.y(), b.x.z(), b.q.w(), b.q.x(), b.q.y(), b.q.z(), b.v.x(),
                     b.v.y(), b.v.z(), b.omega.x(), b.omega.y(), b.omega.z()}) {
      buf += ',';
      append_number(buf, q);
    }
    buf += '\n';
  }
}

void append_stats_row(std::string& buf, long step, double t, const Totals& s) {
  append_int(buf, step);
  for (double q : {t, s.energy(), s.kinetic, s.potential, s.p.x(), s.p.y(), s.p.z(), s.L.x(),
                   s.L.y(), s.L.z()}) {
    buf += ',';
    append_number(buf, q);
  }
  buf += '\n';
}

ordered_json vec_json(const Vec3& v) {
  auto n = [](double x) { return std::isfinite(x) ? ordered_json(x) : ordered_json(nullptr); };
  return {n(v.x()), n(v.y()), n(v.z())};
}

// One run from the scene's initial state (the contract's step loop, wb::run_steps).
wb::Summary simulate(const Scene& scene, const Integrator& integ, const wb::RunRequest& r,
                     wb::RunFiles& files) {
  std::vector<Body> bodies = initial_bodies(scene);
  std::vector<std::string> warnings;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!(bodies[i].I_body.diagonal().minCoeff() > 0)) {
      warnings.push_back("body " + std::to_string(i) +
                         ": its inertia tensor has an entry <= 0 (or NaN): are the R1 inertia "
                         "functions written yet?");
    }
  }
  const Totals t0 = totals(scene, bodies);
  const double scale = wb::energy_scale(t0.kinetic, t0.potential, work_scale(scene, bodies));
  // The stub warnings' questions: did any body move or turn, and did any have a velocity
  // that moves it by more than rounding in a step (kStill: a body hanging at rest on its
  // hinge keeps a velocity of rounding's size, which moves nothing)?
  constexpr double kStill = 1e-9;  // m, or rad, per step
  bool moved = false;
  long mover = -1;  // a body that had such a velocity, the first seen
  double drift = 0;
  StepState state;   // contacts' impulses, kept from step to step
  double angle = 0;  // largest angle of a revolute hinge's body axis from its axis
  const std::vector<Body> first = bodies;
  wb::StepHooks hooks;
  hooks.step = [&] {
    drift = std::max(drift, step(scene, integ, r.dt, bodies, state));
    angle = std::max(angle, state.hinge_angle);
    for (std::size_t i = 0; i < bodies.size() && !moved; ++i) {
      const Body& b = bodies[i];
      moved = b.x != first[i].x || b.q.coeffs() != first[i].q.coeffs();
      if (mover < 0 && (r.dt * b.v.norm() > kStill || r.dt * b.omega.norm() > kStill)) {
        mover = long(i);
      }
    }
  };
  hooks.finite = [&] { return finite(bodies); };
  hooks.energy = [&] { return totals(scene, bodies).energy(); };
  hooks.record = [&](long k, double t) {
    if (files.trace) {
      append_trace_rows(files.trace.rows(), t, bodies);
      files.trace.flush_if_large();
    }
    if (files.stats) {
      append_stats_row(files.stats.rows(), k, t, totals(scene, bodies));
      files.stats.flush_if_large();
    }
  };
  const wb::LoopResult loop = wb::run_steps(r.steps, r.every, r.dt, scale, hooks);
  const long k = loop.steps;
  // No body moved: a stub when one had a velocity (R4 did not move it), or when the
  // scene's forces changed no velocity (R3 or R5 gave nothing). A body held at rest
  // (a pendulum hanging on its hinge) had its velocity changed, then cancelled.
  const bool pulled = scene.g != Vec3::Zero() || !scene.point_forces.empty();
  if (k > 0 && !moved && loop.reason.empty() && mover >= 0) {
    warnings.push_back("no body moved or turned in " + std::to_string(k) +
                       " steps, though body " + std::to_string(mover) +
                       " had a velocity: is integrate_position (R4) still a stub?");
  } else if (k > 0 && !moved && loop.reason.empty() && pulled && !state.velocity_changed) {
    warnings.push_back("no body's velocity changed in " + std::to_string(k) +
                       " steps under the scene's forces: are apply_force and apply_gravity "
                       "(R3) or integrate_velocity (R5) still stubs?");
  }
  const Totals t1 = totals(scene, bodies);
  files.trace.commit();
  files.stats.commit();

  wb::Summary s;
  s.diverged = loop.reason;
  s.steps = k;
  s.t = double(k) * r.dt;
  s.force_evals = k;  // one force accumulation per step
  s.wall_s = loop.wall_s;
  s.cpu_s = loop.cpu_s;
  s.energy0 = t0.energy();
  s.energy = t1.energy();
  s.momentum0 = {t0.p.x(), t0.p.y(), t0.p.z()};
  s.momentum = {t1.p.x(), t1.p.y(), t1.p.z()};
  s.extra = ordered_json::object();
  s.extra["angular_momentum0"] = vec_json(t0.L);
  s.extra["angular_momentum"] = vec_json(t1.L);
  if (!scene.hinges.empty()) {
    s.extra["hinge_drift"] = std::isfinite(drift) ? ordered_json(drift) : ordered_json(nullptr);
  }
  const bool revolute = std::any_of(scene.hinges.begin(), scene.hinges.end(),
                                    [](const Hinge& hg) { return hg.revolute; });
  if (revolute) {
    s.extra["hinge_angle"] = std::isfinite(angle) ? ordered_json(angle) : ordered_json(nullptr);
  }
  s.warnings = warnings;
  return s;
}

// The rigid lab's rates (docs/scenes.md, "Cost"; measured with the solution on the
// default scenes): a body's step (forces, velocities, positions, the totals of the
// divergence rule), one contact point tested against a plane in one pass (or one
// iteration of the accumulated solver and its push-out), a hinge's impulses, and
// the memory of a body.
constexpr double kSecondsPerBodyStep = 200e-9;
constexpr double kSecondsPerPointTest = 30e-9;
// of a touching point (half of them): the solution measured 8.3 us a step on box-rest (4 of 8
// corners touching, 10 iterations: 2026-12-07, tests/badinput/check_cost.py at 2.4 with 50 ns)
constexpr double kSecondsPerPointIteration = 90e-9;
constexpr double kSecondsPerHingeStep = 150e-9;
constexpr double kBytesPerBody = 600;
constexpr double kBytesPerKeptPoint = 100;  // the accumulated solver keeps every point's Contact

std::string count(std::size_t n) { return std::to_string(n); }

}  // namespace

void step_cost(const Scene& scene, wb::StepCost& c) {
  const std::size_t n = scene.bodies.size(), np = scene.planes.size();
  c.once.add("bodies: " + count(n), "bodies", 0, 0, double(n) * kBytesPerBody);
  c.step.add("bodies: " + count(n), "bodies", double(n), kSecondsPerBodyStep);
  if (!scene.hinges.empty()) {
    c.step.add("hinges: " + count(scene.hinges.size()), "hinges", double(scene.hinges.size()),
               kSecondsPerHingeStep);
  }
  if (np > 0) {
    double points = 0;  // contact candidates per plane (contact_points)
    for (const BodyDef& d : scene.bodies) {
      points += d.shape == BodyDef::kSphere ? 1 : d.shape == BodyDef::kBox ? 8 : 32;
    }
    // The passes solver stops when a pass applies no impulse (typically 2, at most
    // kContactPasses); the accumulated one tests every point once, then runs its
    // iterations and as many of push-out on the points that touch.
    const double tests = points * double(np);
    if (scene.solver == Solver::kPasses) {
      c.step.add("contact tests: " + wb::num(points) +
                     " points (8 per box, 1 per sphere, 32 per cylinder) x " + count(np) +
                     " planes x 2 to " + std::to_string(kContactPasses) + " passes",
                 "planes", tests * 2, kSecondsPerPointTest, 0.0, tests * kContactPasses);
    } else {
      c.step.add("contact tests: " + wb::num(points) +
                     " points (8 per box, 1 per sphere, 32 per cylinder) x " + count(np) +
                     " planes, then 2 x " + std::to_string(scene.iterations) +
                     " iterations on those that touch",
                 "contact.iterations", tests,
                 kSecondsPerPointTest + 0.5 * 2.0 * scene.iterations * kSecondsPerPointIteration,
                 tests * kBytesPerKeptPoint, tests * (1 + 2.0 * scene.iterations));
    }
  }
  c.record.add("trace and stats rows: " + count(n) + " bodies", "--out", double(n),
               2 * wb::kSecondsPerTraceRow);
}

namespace {

class RigidScene : public wb::LabScene {
 public:
  RigidScene(const LabInfo& info, Scene scene) : info_(info), scene_(std::move(scene)) {
    file = scene_.file;
    name = scene_.name;
    dt = scene_.dt;
    t_end = scene_.t_end;
    integrator = scene_.integrator;
  }

  void cost(std::size_t /*integrator*/, wb::StepCost& c) const override { step_cost(scene_, c); }

  std::vector<std::string> prepare(const std::vector<std::size_t>& /*integrators*/,
                                   const wb::SweepPlan* sweep) override {
    if (sweep && !scene_.torque_free()) {
      throw InputError("--sweep: " + scene_.file +
                       ": expected a torque-free scene (no forces, planes or hinges): its "
                       "exact angular momentum and energy are the initial ones");
    }
    return initial_overlap_notes(scene_);
  }

  wb::Summary run(const wb::RunRequest& r, wb::RunFiles& files) override {
    return simulate(scene_, info_.integrators.at(r.integrator), r, files);
  }

  // Sweep mode: every integrator over the ladder on a torque-free scene, against the
  // exact conserved angular momentum and energy (docs/sweep.md, "rigid").
  wb::SweepHooks sweep_hooks() override {
    start_ = initial_bodies(scene_);
    t0_ = totals(scene_, start_);
    wb::SweepHooks h;
    h.reset = [this] {
      bodies_ = start_;
      steps_ = 0;
    };
    h.steps = [this](std::size_t i, double dt, long n) {
      const Integrator& integ = info_.integrators.at(i);
      for (long k = 0; k < n; ++k) {
        step(scene_, integ, dt, bodies_);
        wb::budget::step_done();
      }
      steps_ += n;
    };
    h.finite = [this] { return finite(bodies_); };
    h.energy = [this] { return totals(scene_, bodies_).energy(); };
    h.moved = [this] {
      for (std::size_t b = 0; b < bodies_.size(); ++b) {
        if (bodies_[b].x != start_[b].x || bodies_[b].q.coeffs() != start_[b].q.coeffs() ||
            bodies_[b].omega != start_[b].omega) {
          return true;
        }
      }
      return false;
    };
    h.evals = [this] { return steps_; };  // one force accumulation per step
    h.unconverged = [] { return 0L; };
    h.error = [this](double) {
      return (totals(scene_, bodies_).L - t0_.L).norm() / std::max(t0_.L.norm(), 1e-300);
    };
    h.energy0 = t0_.energy();
    h.energy_scale = std::max(t0_.energy(), 1e-300);
    h.blowup_scale = wb::energy_scale(t0_.kinetic, t0_.potential, work_scale(scene_, start_));
    h.reference = "exact";
    h.unmoved = "its errors of 0 mean nothing (are R4 and R5 still stubs?)";
    return h;
  }

 private:
  const LabInfo& info_;
  Scene scene_;
  std::vector<Body> start_, bodies_;  // sweep mode: the initial and the current state
  Totals t0_;
  long steps_ = 0;
};

}  // namespace

int run_rigid_lab(int argc, char** argv, const LabInfo& info) {
  wb::LabSpec spec;
  spec.lab = info.lab;
  spec.side = info.side;
  spec.summary = info.summary;
  for (const Integrator& it : info.integrators)
    spec.integrators.push_back({it.name, it.description, 1, 1});
  spec.help_sections = {
      "Scene keys: bodies (shape box|sphere|cylinder, size|radius|length, m, x, v, q, omega),\n"
      "forces (type gravity: g; type force: body, point, F), planes (point, normal),\n"
      "contact (restitution, friction, solver accumulated|passes, iterations, resting_speed),\n"
      "hinges (body, anchor, beta; with axis: revolute, without: a point (ball) joint).\n"
      "See docs/scenes.md.\n",
      "Trace (--out): t,id,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz (omega in the world frame).\n"
      "Stats (--stats): step,t,energy,kinetic,potential,px,py,pz,Lx,Ly,Lz (L about the "
      "origin).\n"};
  spec.trace_columns = "t,id,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";
  spec.stats_columns = "step,t,energy,kinetic,potential,px,py,pz,Lx,Ly,Lz";
  spec.sweep = true;
  spec.sweep_scenes = "on a torque-free scene";
  spec.sweep_errors =
      "On a torque-free scene only: error = |L(T) - L0| / |L0|,\n"
      "energy_error = max |E - E0| / E0 (the exact values are the initial ones).";
  return wb::run_lab(argc, argv, spec,
                     [&info](const wb::RunFlags& flags) -> std::unique_ptr<wb::LabScene> {
                       return std::make_unique<RigidScene>(info, load_scene(flags.scene_file));
                     });
}

}  // namespace rigid
