// The run contract's state-independent parts (wb/contract.h).
#include "wb/contract.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <iostream>
#include <limits>
#include <new>

#include "wb/budget.h"
#include "wb/output.h"

namespace wb {

namespace {

std::string fmt(double x) {
  std::string s;
  append_number(s, x);
  return s;
}

ordered_json number_or_null(double x) {
  return std::isfinite(x) ? ordered_json(x) : ordered_json(nullptr);
}

// A CSV field: quoted only when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

double energy_scale(double kinetic0, double potential0, double work0) {
  const double total = std::abs(kinetic0 + potential0);
  const double parts = std::abs(kinetic0) + std::abs(potential0);
  double s = 0;
  for (double c : {total, parts, std::abs(work0)}) {
    if (std::isfinite(c)) s = std::max(s, c);
  }
  return s;
}

std::string divergence(bool state_finite, double energy, double scale, long step) {
  if (!diverges(state_finite, energy, scale)) return "";
  if (!state_finite) return "the state is not finite at step " + std::to_string(step);
  if (!std::isfinite(energy)) return "the energy is not finite at step " + std::to_string(step);
  if (std::abs(energy) > kBlowUpFactor * scale) {
    return "|E| = " + fmt(std::abs(energy)) + " J at step " + std::to_string(step) +
           ", more than " + fmt(kBlowUpFactor) + " times the initial energy scale " + fmt(scale) +
           " J";
  }
  return "";
}

std::string unconverged_divergence(long steps, long unconverged) {
  if (steps <= 0 || !(double(unconverged) > kMaxUnconvergedShare * double(steps))) return "";
  return "the implicit solver did not converge on " + std::to_string(unconverged) + " of " +
         std::to_string(steps) + " steps (more than " +
         std::to_string(int(std::lround(100 * kMaxUnconvergedShare))) + " %)";
}

LoopResult run_steps(long steps, long every, double dt, double scale, const StepHooks& hooks) {
  LoopResult r;
  budget::loop_started();
  budget::PhaseScope phase(budget::kStep);
  const auto record = [&](long k, double t) {
    budget::PhaseScope writing(budget::kOutput);
    hooks.record(k, t);
  };
  record(0, 0.0);
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  long k = 0;
  while (k < steps) {
    hooks.step();
    ++k;
    const double t = double(k) * dt;  // not accumulated: no drift in t
    budget::set_phase(budget::kEnergy);
    const bool finite = hooks.finite();
    r.reason = divergence(finite, finite ? hooks.energy() : NAN, scale, k);
    budget::set_phase(budget::kStep);
    if (!r.reason.empty() || k == steps || k % every == 0) record(k, t);
    budget::step_done();
    if (!r.reason.empty()) break;
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::clock_t cpu_end = std::clock();
  r.cpu_s = cpu_start == std::clock_t(-1) || cpu_end == std::clock_t(-1)
                ? NAN
                : double(cpu_end - cpu_start) / CLOCKS_PER_SEC;
  r.steps = k;
  return r;
}

ordered_json summary_json(const Summary& s) {
  bool finite = std::isfinite(s.energy0) && std::isfinite(s.energy);
  for (const auto* v : {&s.momentum0, &s.momentum})
    for (double c : *v) finite = finite && std::isfinite(c);
  ordered_json j;  // keys in the documented order
  j["status"] = !s.diverged.empty() || !finite ? "diverged" : "ok";
  if (!s.diverged.empty() || !finite) {
    j["diverged"] = s.diverged.empty() ? "a number of the summary is not finite" : s.diverged;
  }
  j["steps"] = s.steps;
  j["t"] = s.t;
  j["force_evals"] = s.force_evals;
  j["wall_s"] = s.wall_s;
  j["cpu_s"] = number_or_null(s.cpu_s);
  j["energy0"] = number_or_null(s.energy0);
  j["energy"] = number_or_null(s.energy);
  for (const auto& [key, v] : {std::pair{"momentum0", &s.momentum0}, {"momentum", &s.momentum}}) {
    ordered_json a = ordered_json::array();
    for (double c : *v) a.push_back(number_or_null(c));
    j[key] = a;
  }
  if (s.extra.is_object()) {
    for (const auto& [key, value] : s.extra.items()) j[key] = value;
  }
  if (s.unconverged > 0) j["unconverged"] = s.unconverged;
  // The summary's warnings are what untouched stubs do (docs/run-contract.md): "stub"
  // says so in one key that a figure or a tool can read without parsing sentences.
  if (!s.warnings.empty()) {
    j["stub"] = true;
    j["warnings"] = s.warnings;
  }
  return j;
}

void print_summary(const ordered_json& j) {
  std::cout << j.dump(-1, ' ', false, ordered_json::error_handler_t::replace) << std::endl;
}

void say(const std::string& exe, const char* kind, const std::string& text) {
  std::cerr << one_line(exe + ": " + kind + ": " + text, kMaxMessageBytes + 100) << std::endl;
}

int guarded_main(const std::string& exe, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    budget::finish();  // one line, this one: the watchdog says nothing more
    say(exe, "error", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    budget::finish();
    // Memory the machine could not give (an allocation beyond what it has): a run too
    // large for it, bad input like a limit, never an internal error (wb/budget.h).
    say(exe, "error", budget::out_of_memory_text());
    return 2;
  } catch (const std::exception& e) {
    budget::finish();
    say(exe, "internal error", e.what());
    return 1;
  }
}

std::string integrators_help(const std::vector<IntegratorLine>& list) {
  std::size_t width = 18;
  for (const IntegratorLine& it : list) width = std::max(width, it.name.size() + 2);
  std::string s = "\nIntegrators (--integrator):\n";
  for (const IntegratorLine& it : list) {
    s += "  " + it.name + std::string(width - it.name.size(), ' ') + it.description + " (order " +
         std::to_string(it.order) + ", " + std::to_string(it.evals_per_step) +
         " force evaluation" + (it.evals_per_step == 1 ? "" : "s") + " per step)\n";
  }
  if (!list.empty()) s += "  default: " + list.front().name + "\n";
  return s;
}

std::string sweep_help(const std::string& what) {
  return "\nSweep mode (--sweep FILE.csv): every integrator (or --integrators a,b) at every\n"
         "step size (--dts list, or dt*2^k for k = 3..-6 from --dt or the scene's dt) to\n"
         "t_end; one row per run: scene,integrator,dt,steps,force_evals,wall_s,error,\n"
         "energy_error,reference,status. " +
         what + " A run that diverges (docs/run-contract.md) has status diverged. See\n" +
         "docs/sweep.md.\n";
}

std::string budget_help() {
  return "\nCost (docs/scenes.md, \"Cost\"): every run and sweep is estimated before it starts,\n"
         "and measured while it runs. Estimated above --max-time (default 3600 s of CPU, with\n"
         "every iteration at its cap) or --max-memory (default 2048 MiB) it is refused; above a\n"
         "minute or half the memory it warns. Whatever the estimate, a run whose CPU time or\n"
         "resident memory reaches its limit stops there: exit 2, one line naming the phase that\n"
         "costs and the total it was heading for. --estimate prints the estimate as JSON and\n"
         "runs nothing.\n";
}

SweepPlan plan_sweep(const std::vector<std::string>& names,
                     const std::vector<std::string>& wanted, const std::vector<double>& dts,
                     std::optional<double> dt, std::optional<double> t_end,
                     std::optional<double> scene_dt, std::optional<double> scene_t_end,
                     const std::string& scene_file, int repeats) {
  SweepPlan p;
  if (wanted.empty()) {
    for (std::size_t i = 0; i < names.size(); ++i) p.integrators.push_back(i);
  } else {
    for (const std::string& w : wanted) {
      const auto it = std::find(names.begin(), names.end(), w);
      if (it == names.end()) {
        std::string known;
        for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
        throw InputError("--integrators: got \"" + w + "\", expected one of: " + known);
      }
      p.integrators.push_back(std::size_t(it - names.begin()));
    }
  }
  if (!(repeats >= 1)) {
    throw InputError("--repeats: got " + std::to_string(repeats) +
                     ", expected a whole number >= 1");
  }
  const double T = t_end ? *t_end : scene_t_end.value_or(-1.0);
  if (!(T > 0.0 && std::isfinite(T))) {
    throw InputError(t_end ? "--t-end: got " + fmt(T) + ", expected a number > 0 for a sweep"
                           : scene_file + ": t_end: " +
                                 (scene_t_end ? "got " + fmt(T) : std::string("missing")) +
                                 ", expected a number > 0 for a sweep (or pass --t-end)");
  }
  p.t_end = T;
  p.dts = dts;
  if (p.dts.empty()) {
    if (!dt && !scene_dt) {
      throw InputError(scene_file +
                       ": dt: missing, expected a number > 0 (or pass --dt or --dts)");
    }
    for (int k = 3; k >= -6; --k) p.dts.push_back(std::ldexp(dt ? *dt : *scene_dt, k));
  }
  // Who chose the step sizes, for the messages below.
  p.ladder =
      dts.empty() ? (dt ? std::string("--dt") : scene_file + ": dt") : std::string("--dts");
  const std::string& ladder = p.ladder;
  for (double h : p.dts) {
    if (!(std::isfinite(h) && h > 0.0)) {
      throw InputError("--dts: got " + fmt(h) + ", expected step sizes > 0");
    }
    const double n = std::round(T / h);
    if (!(n >= 1.0 && n <= double(kMaxSteps))) {
      throw InputError(ladder + ": step " + fmt(h) + " gives round(T/dt) = " + fmt(n) +
                       " steps for T = " + fmt(T) + ", expected 1 to " +
                       std::to_string(kMaxSteps));
    }
    p.steps.push_back(long(n));
  }
  return p;
}

std::string sweep_columns() {
  return "scene,integrator,dt,steps,force_evals,wall_s,error,energy_error,reference,status";
}

std::string sweep_table(const std::string& scene, const std::vector<std::string>& names,
                        const std::vector<SweepRow>& rows, bool header) {
  std::string out = header ? sweep_columns() + "\n" : "";
  for (const SweepRow& row : rows) {
    out += csv_field(scene) + ',' + csv_field(names.at(row.integrator)) + ',';
    append_number(out, row.dt);
    out += ',';
    append_int(out, row.steps);
    out += ',';
    append_int(out, row.force_evals);
    for (double q : {row.wall_s, row.error, row.energy_error}) {
      out += ',';
      append_number(out, q);
    }
    out += ',' + row.reference + ',' + (row.diverged ? "diverged" : "ok") + '\n';
  }
  return out;
}

ordered_json sweep_summary(const std::string& csv, const std::vector<SweepRow>& rows) {
  ordered_json j;
  j["status"] = "ok";
  j["sweep"] = csv;
  j["runs"] = rows.size();
  j["diverged"] =
      std::count_if(rows.begin(), rows.end(), [](const SweepRow& r) { return r.diverged; });
  return j;
}

std::vector<SweepRow> sweep_rows(const SweepPlan& plan, const std::vector<std::string>& names,
                                 const SweepHooks& h, const std::string& exe, int repeats) {
  budget::loop_started();
  const budget::PhaseScope stepping(budget::kStep);
  std::vector<SweepRow> rows;
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t i : plan.integrators) {
    for (std::size_t d = 0; d < plan.dts.size(); ++d) {
      SweepRow row;
      row.integrator = i;
      row.dt = plan.dts[d];
      row.steps = plan.steps[d];
      row.reference = h.reference;

      // Untimed run: divergence (the run contract's rule), the largest energy error.
      h.reset();
      double energy_error = 0;
      for (long k = 0; k < row.steps; ++k) {
        h.steps(i, row.dt, 1);
        const budget::PhaseScope checking(budget::kEnergy);
        const bool finite = h.finite();
        const double E = finite ? h.energy() : NAN;
        if (!divergence(finite, E, h.blowup_scale, k + 1).empty()) {
          row.diverged = true;
          break;
        }
        energy_error = std::max(energy_error, std::abs(E - h.energy0) / h.energy_scale);
      }
      row.diverged = row.diverged || !unconverged_divergence(row.steps, h.unconverged()).empty();
      if (row.steps > 0 && !row.diverged && !h.moved()) {
        say(exe, "warning",
            names.at(i) + " at dt=" + fmt(row.dt) + ": the state never changed in " +
                std::to_string(row.steps) + " steps: " + h.unmoved);
      }
      row.energy_error = row.diverged ? inf : energy_error;
      {
        const budget::PhaseScope reference(budget::kReference);
        row.error = row.diverged ? inf : h.error(double(row.steps) * row.dt);
      }

      // Timed runs: the pure step loop, the fastest of `repeats`.
      row.wall_s = inf;
      for (int r = 0; r < repeats; ++r) {
        h.reset();
        const auto start = std::chrono::steady_clock::now();
        h.steps(i, row.dt, row.steps);
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        row.wall_s = std::min(row.wall_s, wall);
        row.force_evals = h.evals();
      }
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace wb
