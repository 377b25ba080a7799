// The run contract for the rigid lab (docs/run-contract.md, "The rigid lab"):
// the same flags, rules, atomic outputs and summary line as the particle labs,
// with a 3D state. Sweep mode: work-precision on a torque-free body.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>

#include "rigid_world.h"
#include "wb/cli.h"
#include "wb/output.h"
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

struct RunOptions {
  const Integrator* integrator = nullptr;
  double dt = 0;
  long steps = 0, every = 1;
  std::string out, stats;
};

// The floor of the run's energy scale (wb::energy_scale): the work gravity
// and the point forces would do across the scene, sum of (m |g| + |F|) times
// the scene size (the extent of the centres or their largest distance from
// the origin; 1 m when both are 0).
double work_scale(const Scene& scene, const std::vector<Body>& bodies) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = -lo;
  double far = 0, force = 0;
  for (const Body& b : bodies) {
    lo = lo.cwiseMin(b.x);
    hi = hi.cwiseMax(b.x);
    far = std::max(far, b.x.norm());
    force += b.m * scene.g.norm();
  }
  for (const PointForce& f : scene.point_forces) force += f.F.norm();
  double S = bodies.empty() ? 0.0 : std::max((hi - lo).norm(), far);
  if (!(std::isfinite(S) && S > 0)) S = 1.0;
  return std::isfinite(force * S) ? force * S : 0.0;
}

ordered_json vec_json(const Vec3& v) {
  auto n = [](double x) { return std::isfinite(x) ? ordered_json(x) : ordered_json(nullptr); };
  return {n(v.x()), n(v.y()), n(v.z())};
}

ordered_json simulate(const Scene& scene, const RunOptions& opt,
                      std::vector<std::string>& warnings) {
  std::vector<Body> bodies = initial_bodies(scene);
  wb::CsvFile trace(opt.out, "t,id,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n");
  wb::CsvFile stats(opt.stats, "step,t,energy,kinetic,potential,px,py,pz,Lx,Ly,Lz\n");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!(bodies[i].I_body.diagonal().minCoeff() > 0)) {
      warnings.push_back("body " + std::to_string(i) +
                         ": its inertia tensor has an entry <= 0 (or NaN): are the R1 inertia "
                         "functions written yet?");
    }
  }
  const Totals t0 = totals(scene, bodies);
  const double scale = wb::energy_scale(t0.kinetic, t0.potential, work_scale(scene, bodies));
  bool moved = false;
  double drift = 0;
  StepState state;   // contacts' impulses, kept from step to step
  double angle = 0;  // largest angle of a revolute hinge's body axis from its axis
  const Body first = bodies.front();
  wb::StepHooks hooks;
  hooks.step = [&] {
    drift = std::max(drift, step(scene, *opt.integrator, opt.dt, bodies, state));
    angle = std::max(angle, state.hinge_angle);
    moved = moved || bodies.front().x != first.x || bodies.front().q.coeffs() != first.q.coeffs();
  };
  hooks.finite = [&] { return finite(bodies); };
  hooks.energy = [&] { return totals(scene, bodies).energy(); };
  hooks.record = [&](long k, double t) {
    if (trace) {
      append_trace_rows(trace.rows(), t, bodies);
      trace.flush_if_large();
    }
    if (stats) {
      append_stats_row(stats.rows(), k, t, totals(scene, bodies));
      stats.flush_if_large();
    }
  };
  const wb::LoopResult loop = wb::run_steps(opt.steps, opt.every, opt.dt, scale, hooks);
  const long k = loop.steps;
  if (k > 0 && !moved && loop.reason.empty()) {
    warnings.push_back("body 0 never moved or turned in " + std::to_string(k) +
                       " steps: is integrate_position (R4) still a stub?");
  }
  const Totals t1 = totals(scene, bodies);
  trace.commit();
  stats.commit();

  wb::Summary s;
  s.diverged = loop.reason;
  s.steps = k;
  s.t = double(k) * opt.dt;
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
  return wb::summary_json(s);
}

// ---- Sweep mode: every integrator over a ladder of step sizes on a torque-free scene,
// against the exact conserved angular momentum and energy (docs/sweep.md, "rigid"). The
// plan, the table and the summary are the contract's (wb/contract.h); only the state and
// the errors are this lab's.

std::vector<wb::SweepRow> run_sweep(const LabInfo& info, const Scene& scene,
                                    const wb::SweepPlan& plan, int repeats) {
  if (!scene.torque_free()) {
    throw InputError("--sweep: " + scene.file +
                     ": expected a torque-free scene (no forces, planes or hinges): its exact "
                     "angular momentum and energy are the initial ones");
  }
  const std::vector<Body> start = initial_bodies(scene);
  const Totals t0 = totals(scene, start);
  const double Lscale = std::max(t0.L.norm(), 1e-300), Escale = std::max(t0.energy(), 1e-300);
  const double blowup_scale =
      wb::energy_scale(t0.kinetic, t0.potential, work_scale(scene, start));
  std::vector<wb::SweepRow> rows;
  const std::size_t total = plan.integrators.size() * plan.dts.size();
  for (std::size_t i : plan.integrators) {
    const Integrator& integ = info.integrators[i];
    for (std::size_t d = 0; d < plan.dts.size(); ++d) {
      wb::SweepRow row;
      row.integrator = i;
      row.dt = plan.dts[d];
      row.steps = row.force_evals = plan.steps[d];
      row.reference = "exact";
      const double h = row.dt;
      std::cerr << "sweep: " << integ.name << " dt=" << num(h) << " (" << rows.size() + 1 << "/"
                << total << ")\n";
      // Timed: the pure step loop, fastest of `repeats`.
      row.wall_s = INFINITY;
      for (int r = 0; r < repeats; ++r) {
        std::vector<Body> bodies = start;
        const auto t_start = std::chrono::steady_clock::now();
        for (long k = 0; k < row.steps; ++k) step(scene, integ, h, bodies);
        row.wall_s = std::min(
            row.wall_s,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count());
      }
      // Untimed: the errors along the run, and the contract's rule for a diverged run.
      std::vector<Body> bodies = start;
      double e_err = 0;
      for (long k = 0; k < row.steps && !row.diverged; ++k) {
        step(scene, integ, h, bodies);
        const bool ok = finite(bodies);
        const double E = ok ? totals(scene, bodies).energy() : NAN;
        row.diverged = !wb::divergence(ok, E, blowup_scale, k + 1).empty();
        if (!row.diverged) e_err = std::max(e_err, std::abs(E - t0.energy()));
      }
      bool moved = false;
      for (std::size_t b = 0; b < bodies.size(); ++b) {
        moved = moved || bodies[b].x != start[b].x ||
                bodies[b].q.coeffs() != start[b].q.coeffs() || bodies[b].omega != start[b].omega;
      }
      if (row.steps > 0 && !moved && !row.diverged) {
        std::cerr << "sweep: warning: " << integ.name << " at dt=" << num(h)
                  << ": no body moved or turned in " << row.steps
                  << " steps: its errors of 0 mean nothing (are R4 and R5 still stubs?)\n";
      }
      row.error = row.diverged ? INFINITY : (totals(scene, bodies).L - t0.L).norm() / Lscale;
      row.energy_error = row.diverged ? INFINITY : e_err / Escale;
      rows.push_back(row);
    }
  }
  return rows;
}

std::string help_footer(const LabInfo& info) {
  std::vector<wb::IntegratorLine> lines;
  for (const Integrator& it : info.integrators) lines.push_back({it.name, it.description, 1, 1});
  std::string s = wb::integrators_help(lines);
  s +=
      "\nScene keys: bodies (shape box|sphere|cylinder, size|radius|length, m, x, v, q, omega),\n"
      "forces (type gravity: g; type force: body, point, F), planes (point, normal),\n"
      "contact (restitution, friction, solver accumulated|passes, iterations, resting_speed),\n"
      "hinges (body, anchor, beta; with axis: revolute, without: a point (ball) joint).\n"
      "See docs/scenes.md.\n";
  s += "\nTrace (--out): t,id,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz (omega in the world frame).\n"
       "Stats (--stats): step,t,energy,kinetic,potential,px,py,pz,Lx,Ly,Lz (L about the "
       "origin).\n";
  s += wb::sweep_help(
      "On a torque-free scene only: error = |L(T) - L0| / |L0|,\n"
      "energy_error = max |E - E0| / E0 (the exact values are the initial ones).");
  return s + wb::help_scenes_and_docs(info.lab);
}

}  // namespace

int run_rigid_lab(int argc, char** argv, const LabInfo& info) {
  wb::FlagSpec spec;
  spec.exe = info.lab + (info.side == "student" ? "" : "-" + info.side);
  spec.summary = info.summary;
  spec.footer = help_footer(info);
  spec.trace_columns = "t,id,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";
  spec.stats_columns = "step,t,energy,kinetic,potential,px,py,pz,Lx,Ly,Lz";
  spec.sweep = true;
  spec.sweep_help =
      "Sweep mode: run the integrators over a ladder of step sizes (default dt*2^k, "
      "k = 3..-6) to t_end on a torque-free scene and write one CSV row per run";
  int status = 0;
  const std::optional<wb::RunFlags> flags = wb::parse_run_flags(argc, argv, spec, status);
  if (!flags) return status;
  const std::string& exe = spec.exe;

  return wb::guarded_main(exe, [&] {
    const Scene scene = load_scene(flags->scene_file);
    if (!flags->sweep_csv.empty()) {
      std::vector<std::string> names;
      for (const Integrator& it : info.integrators) names.push_back(it.name);
      const int repeats = flags->repeats.value_or(3);
      const wb::SweepPlan plan =
          wb::plan_sweep(names, flags->sweep_integrators, flags->sweep_dts, flags->dt,
                         flags->t_end, scene.dt, scene.t_end, scene.file, repeats);
      wb::AtomicFile csv(flags->sweep_csv);  // an unwritable path fails before the runs
      for (const auto& w : scene.cost_warnings) std::cerr << exe << ": warning: " << w << "\n";
      const std::vector<wb::SweepRow> rows = run_sweep(info, scene, plan, repeats);
      csv.write(wb::sweep_table(scene.name, names, rows));
      csv.commit();
      std::cout << wb::sweep_summary(flags->sweep_csv, rows).dump() << std::endl;
      return 0;
    }

    RunOptions opt;
    opt.integrator =
        &wb::choose_integrator(info.integrators, *flags, scene.integrator, scene.file);
    opt.dt = wb::step_size(*flags, scene.dt, scene.file);
    opt.steps = wb::steps_to_take(*flags, scene.t_end, scene.file, opt.dt);
    opt.every = flags->every.value_or(1);
    opt.out = flags->out;
    opt.stats = flags->stats;
    for (const auto& w : scene.cost_warnings) std::cerr << exe << ": warning: " << w << "\n";
    std::vector<std::string> warnings;
    const ordered_json j = simulate(scene, opt, warnings);
    for (const auto& w : warnings) std::cerr << exe << ": warning: " << w << "\n";
    std::cout << j.dump() << std::endl;
    return 0;
  });
}

}  // namespace rigid
