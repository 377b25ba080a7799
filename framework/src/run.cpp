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

void check_output_path(const std::string& flag, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path p(path);
  if (path.empty()) throw InputError(flag + ": got an empty path, expected a file name");
  if (fs::is_directory(p, ec)) {
    throw InputError(flag + ": got \"" + path + "\", a folder, expected a file name");
  }
  const fs::file_status st = fs::status(p, ec);
  if (!ec && fs::exists(st) && !fs::is_regular_file(st)) {  // /dev/null, a FIFO: written through
    if (::access(path.c_str(), W_OK) != 0) {
      throw InputError(flag + ": got \"" + path + "\", expected a file you can write");
    }
    return;
  }
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec)) {
    throw InputError(flag + ": got \"" + path + "\", expected a file in an existing folder (\"" +
                     dir.string() + "\" does not exist)");
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    throw InputError(flag + ": got \"" + path +
                     "\", expected a file in a folder you can write (\"" + dir.string() +
                     "\" is not writable)");
  }
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
  // Decimal digits only: no sign, no base prefix (010 is ten), no exponent,
  // no silent clamping of a value that does not fit.
  const std::string expected =
      "a whole number from " + std::to_string(min) + " to " + std::to_string(max);
  // At most 19 significant digits (< 10^19 < 2^64): the value fits a uint64.
  const std::size_t first = std::min(text.find_first_not_of('0'), text.size());
  bool digits = !text.empty() && text.size() - first <= 19;
  std::uint64_t value = 0;
  for (std::size_t i = first; digits && i < text.size(); ++i) {
    const char c = text[i];
    digits = c >= '0' && c <= '9';
    value = value * 10 + std::uint64_t(c - '0');
  }
  if (!digits || max < 0 || value > std::uint64_t(max) || std::int64_t(value) < min) {
    throw InputError(flag + ": got \"" + text + "\", expected " + expected + " (decimal digits)");
  }
  return std::int64_t(value);
}

void check_initial_state(const Scene& scene, const World& world) {
  const Energy e = world.energy(scene.x, scene.v);
  const Vec2 p = momentum(scene.v, scene.m);
  if (std::isfinite(e.kinetic) && std::isfinite(e.potential) && std::isfinite(e.total()) &&
      p.allFinite()) {
    return;
  }
  throw InputError(scene.file + ": initial state: kinetic energy " + num(e.kinetic) +
                   ", potential energy " + num(e.potential) + ", momentum [" + num(p.x()) + ", " +
                   num(p.y()) +
                   "], expected finite values (a position, velocity, mass or force constant "
                   "is so large that they overflow)");
}

double particle_work_scale(const Scene& scene, const World& world) {
  // The scene size S: the extent of the initial positions or their largest
  // distance from the origin, 1 m when both are 0 (tools/wbplot/recipes.py's
  // length_scale, the report's scene size).
  double S = 0;
  if (scene.n() > 0) {
    const Vec2 lo = scene.x.rowwise().minCoeff(), hi = scene.x.rowwise().maxCoeff();
    S = std::max((hi - lo).norm(), scene.x.colwise().norm().maxCoeff());
  }
  if (!(std::isfinite(S) && S > 0)) S = 1.0;
  const Dynamics& dyn = world.dynamics();
  Mat2X a(2, scene.n());
  dyn.acceleration(scene.x, scene.v, a);
  dyn.reset_evals();
  const double work = (a.colwise().norm().transpose().array() * scene.m.array()).sum() * S;
  return std::isfinite(work) ? work : 0.0;
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

  CsvFile trace(opt.out, "t,id,x,y,vx,vy\n");
  CsvFile stats(opt.stats, "step,t,energy,kinetic,potential,px,py,force_evals\n");
  // Did any step change the state? Compared with the state before the step,
  // which is the scene's own until a step moves it (or the collision phase
  // does: then a copy), so that the check copies nothing on a normal run.
  bool moved = false;
  const Mat2X *x_before = &scene.x, *v_before = &scene.v;
  Mat2X x_phase, v_phase;
  StepHooks hooks;
  hooks.step = [&] {
    opt.integrator->step(dyn, opt.dt, x, v, scratch);
    if (!moved) moved = x != *x_before || v != *v_before;
    world.after_step(opt.dt, x, v);
    if (!moved && (x != *x_before || v != *v_before)) {
      x_phase = x;
      v_phase = v;
      x_before = &x_phase;
      v_before = &v_phase;
    }
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
  if (k > 0 && !moved && scene.n() > 0) {
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

namespace {

ordered_json summary_json(const RunResult& r) {
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
  return wb::summary_json(s);
}

std::string help_footer(const LabInfo& info) {
  std::vector<IntegratorLine> lines;
  for (const Integrator& it : info.integrators) {
    lines.push_back({it.name, it.description, it.order, it.evals_per_step});
  }
  std::string s = integrators_help(lines);
  for (const auto& section : info.help_sections) s += "\n" + section;
  if (info.sweep) {
    s += sweep_help(
        "Errors against the scene's \"exact\" motion or an RK4 run at the smallest\n"
        "dt/16.");
  }
  return s + help_scenes_and_docs(info.lab);
}

}  // namespace

int run_particle_lab(int argc, char** argv, const LabInfo& info) {
  FlagSpec spec;
  spec.exe = info.lab + (info.side == "student" ? "" : "-" + info.side);
  spec.summary = info.summary;
  spec.footer = help_footer(info);
  spec.trace_columns = "t,id,x,y,vx,vy";
  spec.stats_columns = "step,t,energy,kinetic,potential,px,py,force_evals";
  spec.seed = true;
  spec.sweep = info.sweep;
  spec.sweep_help =
      "Sweep mode: run the integrators over a ladder of step sizes (default dt*2^k, "
      "k = 3..-6) to t_end and write one CSV row per run";
  int status = 0;
  const std::optional<RunFlags> flags = parse_run_flags(argc, argv, spec, status);
  if (!flags) return status;
  const std::string& exe = spec.exe;

  return guarded_main(exe, [&] {
    std::vector<std::string> keys = info.scene_keys;
    if (info.sweep) keys.insert(keys.end(), sweep_scene_keys().begin(), sweep_scene_keys().end());
    Scene scene = load_scene(flags->scene_file, flags->seed, keys);
    if (info.expand_scene) {
      info.expand_scene(scene);
      check_particles(scene, "the scene's generators");
    }
    if (!info.make_world) throw std::logic_error("LabInfo.make_world is not set");
    std::unique_ptr<World> world = info.make_world(scene);
    check_initial_state(scene, *world);
    if (info.sweep) read_exact(scene);  // checks the "exact" key in every mode
    if (!flags->sweep_csv.empty()) {
      SweepOptions sweep;
      sweep.csv = flags->sweep_csv;
      sweep.integrators = flags->sweep_integrators;
      sweep.dts = flags->sweep_dts;
      if (flags->repeats) sweep.repeats = *flags->repeats;
      sweep.dt = flags->dt;
      sweep.t_end = flags->t_end;
      sweep.exe = exe;
      sweep.warnings = world->cost_warnings;
      const SweepResult sr = run_sweep(info, scene, *world, sweep);
      std::cout << sweep_summary(sweep.csv, sr.rows).dump() << std::endl;
      return 0;
    }

    RunOptions opt;
    opt.integrator = &choose_integrator(info.integrators, *flags, scene.integrator, scene.file);
    opt.dt = step_size(*flags, scene.dt, scene.file);
    opt.steps = steps_to_take(*flags, scene.t_end, scene.file, opt.dt);
    opt.every = flags->every.value_or(1);
    opt.out = flags->out;
    opt.stats = flags->stats;

    // Accepted: what will be slow is said now, once, before the run.
    std::vector<std::string> warnings = world->cost_warnings;
    if (opt.integrator->check) {
      const std::string w = opt.integrator->check(*opt.integrator, world->dynamics());
      if (!w.empty()) warnings.push_back(w);
    }
    const double work = double(opt.steps) * double(scene.n());
    if (work > kLongRunParticleSteps) {
      warnings.push_back(std::to_string(opt.steps) + " steps of " + std::to_string(scene.n()) +
                         " particles (" + num(work) +
                         " particle-steps): this run may take minutes or more");
    }
    for (const auto& w : warnings) std::cerr << exe << ": warning: " << w << "\n";
    RunResult r = simulate(scene, *world, opt);
    for (const auto& w : r.warnings) std::cerr << exe << ": warning: " << w << "\n";
    std::cout << summary_json(r).dump() << std::endl;
    return 0;
  });
}

}  // namespace wb
