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

ordered_json number_or_null(double x) {
  return std::isfinite(x) ? ordered_json(x) : ordered_json(nullptr);
}
ordered_json vec_json(const Vec3& v) {
  return {number_or_null(v.x()), number_or_null(v.y()), number_or_null(v.z())};
}

struct RunOptions {
  const Integrator* integrator = nullptr;
  double dt = 0;
  long steps = 0, every = 1;
  std::string out, stats;
};

ordered_json simulate(const Scene& scene, const RunOptions& opt,
                      std::vector<std::string>& warnings) {
  std::vector<Body> bodies = initial_bodies(scene);
  wb::CsvFile trace(opt.out, "t,id,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n");
  wb::CsvFile stats(opt.stats, "step,t,energy,kinetic,potential,px,py,pz,Lx,Ly,Lz\n");
  auto record = [&](long k, double t) {
    if (trace) {
      append_trace_rows(trace.rows(), t, bodies);
      trace.flush_if_large();
    }
    if (stats) {
      append_stats_row(stats.rows(), k, t, totals(scene, bodies));
      stats.flush_if_large();
    }
  };
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!(bodies[i].I_body.diagonal().minCoeff() > 0)) {
      warnings.push_back("body " + std::to_string(i) +
                         ": its inertia tensor has an entry <= 0 (or NaN): are the R1 inertia "
                         "functions written yet?");
    }
  }
  const Totals t0 = totals(scene, bodies);
  record(0, 0.0);
  const auto start = std::chrono::steady_clock::now();
  long k = 0;
  bool diverged = false, moved = false;
  double drift = 0;
  StepState state;   // contacts' impulses, kept from step to step
  double angle = 0;  // largest angle of a revolute hinge's body axis from its axis
  const Body first = bodies.front();
  while (k < opt.steps) {
    drift = std::max(drift, step(scene, *opt.integrator, opt.dt, bodies, state));
    angle = std::max(angle, state.hinge_angle);
    ++k;
    const double t = double(k) * opt.dt;
    diverged = !finite(bodies);
    moved = moved || bodies.front().x != first.x || bodies.front().q.coeffs() != first.q.coeffs();
    if (diverged || k == opt.steps || k % opt.every == 0) record(k, t);
    if (diverged) break;
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (k > 0 && !moved && !diverged) {
    warnings.push_back("body 0 never moved or turned in " + std::to_string(k) +
                       " steps: is integrate_position (R4) still a stub?");
  }
  const Totals t1 = totals(scene, bodies);
  trace.commit();
  stats.commit();

  ordered_json j;  // keys in the documented order
  j["status"] = diverged ? "diverged" : "ok";
  j["steps"] = k;
  j["t"] = double(k) * opt.dt;
  j["force_evals"] = k;  // one force accumulation per step
  j["wall_s"] = wall;
  j["energy0"] = number_or_null(t0.energy());
  j["energy"] = number_or_null(t1.energy());
  j["momentum0"] = vec_json(t0.p);
  j["momentum"] = vec_json(t1.p);
  j["angular_momentum0"] = vec_json(t0.L);
  j["angular_momentum"] = vec_json(t1.L);
  if (!scene.hinges.empty()) j["hinge_drift"] = number_or_null(drift);
  const bool revolute = std::any_of(scene.hinges.begin(), scene.hinges.end(),
                                    [](const Hinge& hg) { return hg.revolute; });
  if (revolute) j["hinge_angle"] = number_or_null(angle);
  if (!warnings.empty()) j["warnings"] = warnings;
  return j;
}

// ---- Sweep mode: every integrator over a ladder of step sizes on a torque-free scene,
// against the exact conserved angular momentum and energy (docs/sweep.md, "rigid").

struct SweepOptions {
  std::string csv;
  std::vector<std::string> integrators;
  std::vector<double> dts;
  int repeats = 3;
};

ordered_json run_sweep(const LabInfo& info, const Scene& scene, double base_dt, double T,
                       const SweepOptions& opt) {
  if (!scene.torque_free()) {
    throw InputError("--sweep: " + scene.file +
                     ": expected a torque-free scene (no forces, planes or hinges): its exact "
                     "angular momentum and energy are the initial ones");
  }
  if (!(T > 0)) throw InputError("--sweep: t_end: got " + num(T) + ", expected a number > 0");
  std::vector<const Integrator*> integs;
  if (opt.integrators.empty()) {
    for (const Integrator& it : info.integrators) integs.push_back(&it);
  } else {
    for (const std::string& n : opt.integrators) {
      integs.push_back(&wb::find_named(info.integrators, n, "--integrators"));
    }
  }
  std::vector<double> dts = opt.dts;
  if (dts.empty()) {
    for (int k = 3; k >= -6; --k) dts.push_back(std::ldexp(base_dt, k));
  }
  const std::string ladder = opt.dts.empty() ? "--dt" : "--dts";
  for (double h : dts) {
    if (!(std::isfinite(h) && h > 0)) {
      throw InputError(ladder + ": got " + num(h) + ", expected finite numbers > 0");
    }
    const double n = std::round(T / h);
    if (!(n >= 1 && n <= double(wb::kMaxSteps))) {
      throw InputError(ladder + ": step " + num(h) + " gives round(T/dt) = " + num(n) +
                       " steps for T = " + num(T) + ", expected 1 to " +
                       std::to_string(wb::kMaxSteps));
    }
  }
  if (opt.repeats < 1) {
    throw InputError("--repeats: got " + std::to_string(opt.repeats) + ", expected >= 1");
  }
  wb::AtomicFile csv(opt.csv);
  const std::string exe = info.lab + (info.side == "student" ? "" : "-" + info.side);
  for (const auto& w : scene.cost_warnings) std::cerr << exe << ": warning: " << w << "\n";
  std::string buf =
      "scene,integrator,dt,steps,force_evals,wall_s,error,energy_error,reference,"
      "status\n";
  const Totals t0 = totals(scene, initial_bodies(scene));
  const double Lscale = std::max(t0.L.norm(), 1e-300), Escale = std::max(t0.energy(), 1e-300);
  long runs = 0, diverged_runs = 0;
  for (const Integrator* integ : integs) {
    for (double h : dts) {
      const long steps = long(std::round(T / h));
      std::cerr << "sweep: " << integ->name << " dt=" << num(h) << " (" << runs + 1 << "/"
                << integs.size() * dts.size() << ")\n";
      // Timed: the pure step loop, fastest of `repeats`.
      double wall = 1e300;
      for (int r = 0; r < opt.repeats; ++r) {
        std::vector<Body> bodies = initial_bodies(scene);
        const auto start = std::chrono::steady_clock::now();
        for (long k = 0; k < steps; ++k) step(scene, *integ, h, bodies);
        wall = std::min(
            wall,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      }
      // Untimed: the errors along the run.
      std::vector<Body> bodies = initial_bodies(scene);
      double e_err = 0;
      bool div = false;
      for (long k = 0; k < steps && !div; ++k) {
        step(scene, *integ, h, bodies);
        div = !finite(bodies);
        if (!div) e_err = std::max(e_err, std::abs(totals(scene, bodies).energy() - t0.energy()));
      }
      const double L_err = div ? INFINITY : (totals(scene, bodies).L - t0.L).norm() / Lscale;
      e_err = div ? INFINITY : e_err / Escale;
      ++runs;
      diverged_runs += div;
      buf += scene.name + "," + integ->name + ",";
      append_number(buf, h);
      buf += ",";
      append_int(buf, steps);
      buf += ",";
      append_int(buf, steps);
      for (double q : {wall, L_err, e_err}) {
        buf += ",";
        if (std::isinf(q)) {
          buf += "inf";
        } else {
          append_number(buf, q);
        }
      }
      buf += std::string(",exact,") + (div ? "diverged" : "ok") + "\n";
    }
  }
  csv.write(buf);
  csv.commit();
  ordered_json j;
  j["status"] = "ok";
  j["sweep"] = opt.csv;
  j["runs"] = runs;
  j["diverged"] = diverged_runs;
  return j;
}

std::string help_footer(const LabInfo& info) {
  std::string s = "\nIntegrators (--integrator):\n";
  for (const Integrator& it : info.integrators) {
    s += "  " + it.name + std::string(it.name.size() < 22 ? 22 - it.name.size() : 1, ' ') +
         it.description + " (order 1, 1 force evaluation per step)\n";
  }
  s += "  default: " + info.integrators.front().name + "\n";
  s +=
      "\nScene keys: bodies (shape box|sphere|cylinder, size|radius|length, m, x, v, q, omega),\n"
      "forces (type gravity: g; type force: body, point, F), planes (point, normal),\n"
      "contact (restitution, friction, solver accumulated|passes, iterations, resting_speed),\n"
      "hinges (body, anchor, beta; with axis: revolute, without: a point (ball) joint).\n"
      "See docs/scenes.md.\n";
  s += "\nTrace (--out): t,id,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz (omega in the world frame).\n"
       "Stats (--stats): step,t,energy,kinetic,potential,px,py,pz,Lx,Ly,Lz (L about the "
       "origin).\n";
  s += "\nSweep mode (--sweep FILE.csv): every integrator (or --integrators a,b) at every\n"
       "step size (--dts list, or dt*2^k for k = 3..-6 from --dt or the scene's dt) to\n"
       "t_end, on a torque-free scene; one row per run: scene,integrator,dt,steps,\n"
       "force_evals,wall_s,error,energy_error,reference,status. error = |L(T) - L0| / |L0|,\n"
       "energy_error = max |E - E0| / E0 (the exact values are the initial ones). See "
       "docs/sweep.md.\n";
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

  try {
    const Scene scene = load_scene(flags->scene_file);
    const double h = wb::step_size(*flags, scene.dt, scene.file);
    if (!flags->sweep_csv.empty()) {
      const double T = flags->t_end ? *flags->t_end : scene.t_end.value_or(-1.0);
      if (T < 0) throw InputError(scene.file + ": t_end: missing (or pass --t-end)");
      SweepOptions sweep;
      sweep.csv = flags->sweep_csv;
      sweep.integrators = flags->sweep_integrators;
      sweep.dts = flags->sweep_dts;
      if (flags->repeats) sweep.repeats = *flags->repeats;
      std::cout << run_sweep(info, scene, h, T, sweep).dump() << std::endl;
      return 0;
    }

    RunOptions opt;
    opt.integrator =
        &wb::choose_integrator(info.integrators, *flags, scene.integrator, scene.file);
    opt.dt = h;
    opt.steps = wb::steps_to_take(*flags, scene.t_end, scene.file, h);
    opt.every = flags->every.value_or(1);
    opt.out = flags->out;
    opt.stats = flags->stats;
    for (const auto& w : scene.cost_warnings) std::cerr << exe << ": warning: " << w << "\n";
    std::vector<std::string> warnings;
    const ordered_json j = simulate(scene, opt, warnings);
    for (const auto& w : warnings) std::cerr << exe << ": warning: " << w << "\n";
    std::cout << j.dump() << std::endl;
    return 0;
  } catch (const InputError& e) {
    std::cerr << exe << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << exe << ": internal error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace rigid
