// The run contract's flags: the one file that includes CLI11 (wb/cli.h).
#include "wb/cli.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "wb/contract.h"
#include "wb/output.h"
#include "wb/run.h"

namespace wb {

namespace {

InputError flag_error(const std::string& flag, const std::string& got,
                      const std::string& expected) {
  return InputError(flag + ": got " + got + ", expected " + expected);
}

// A number flag: the whole text one finite number, read by the scene files' reader
// (wb::read_number: JSON's grammar, no blanks, no hex, correctly rounded), else
// InputError naming the flag and the text ("" included).
double parse_number(const std::string& flag, const std::string& text,
                    const std::string& expected) {
  const NumberText t = read_number(text);
  if (!t.valid) {
    throw flag_error(flag, "\"" + text + "\"",
                     expected +
                         " (written as in JSON: digits, an optional fraction and "
                         "exponent; no blanks, no \"+\", no hex)");
  }
  if (t.overflow || t.underflow) {
    throw flag_error(flag, "\"" + text + "\"",
                     expected + (t.overflow ? " (it is too large for a double)"
                                            : " (it is too small for a double: it reads as 0)"));
  }
  return t.value;
}

}  // namespace

RunFlags read_run_flags(int argc, const char* const* argv, const FlagSpec& spec,
                        std::string& help) {
  CLI::App app(spec.summary, spec.exe);
  RunFlags f;
  help.clear();
  // Whole numbers are read as text and parsed strictly (parse_whole).
  std::optional<std::string> steps_in, every_in, seed_in, repeats_in, dt_in, t_end_in;
  std::optional<std::string> max_time_in, max_memory_in;
  std::vector<std::string> dts_in;
  app.add_option("--scene", f.scene_file, "Scene file (JSON)")->required();
  auto* o_integrator =
      app.add_option("--integrator", f.integrator, "Integrator name (overrides the scene's)");
  auto* o_dt = app.add_option(
      "--dt", dt_in,
      "Step size H > 0 (overrides the scene's dt; with --sweep, the ladder's base)");
  auto* o_steps = app.add_option("--steps", steps_in, "Take exactly N steps (at most 1e8)");
  auto* o_tend = app.add_option("--t-end", t_end_in, "Simulate to time T: steps = round(T/H)");
  o_steps->excludes(o_tend);
  auto* o_out = app.add_option("--out", f.out, "Write a CSV trace " + spec.trace_columns);
  auto* o_stats = app.add_option("--stats", f.stats, "Write a CSV of " + spec.stats_columns);
  auto* o_every = app.add_option("--every", every_in,
                                 "With --out or --stats: write every K-th step (step 0 and the "
                                 "last always)");
  if (spec.seed)
    app.add_option("--seed", seed_in, "Emitter k uses seed S + k instead of its own");
  app.add_option(
      "--max-time", max_time_in,
      "CPU seconds a run (or sweep) may take: refused when estimated above, stopped when "
      "it gets there (default 3600)");
  app.add_option(
      "--max-memory", max_memory_in,
      "MiB of memory a run (or sweep) may hold: refused when estimated above, stopped when "
      "it gets there (default 2048)");
  app.add_flag("--estimate", f.estimate,
               "Print the cost model's estimate as one JSON line and run nothing");
  CLI::Option *o_sweep = nullptr, *o_integrators = nullptr, *o_dts = nullptr;
  if (spec.sweep) {
    o_sweep = app.add_option("--sweep", f.sweep_csv, spec.sweep_help);
    o_integrators = app.add_option("--integrators", f.sweep_integrators,
                                   "Sweep: only these integrators (comma-separated; default all)")
                        ->delimiter(',')
                        ->needs(o_sweep);
    o_dts = app.add_option("--dts", dts_in,
                           "Sweep: these step sizes (comma-separated; instead of --dt's ladder)")
                ->delimiter(',')
                ->needs(o_sweep);
    // --dt is the base of the default ladder: beside --dts it would be ignored.
    o_dts->excludes(o_dt);
    app.add_option("--repeats", repeats_in,
                   "Sweep: wall_s is the fastest of R timed step loops (default 3)")
        ->needs(o_sweep);
    for (CLI::Option* o : {o_integrator, o_steps, o_out, o_stats, o_every}) o_sweep->excludes(o);
  }
  app.footer(spec.footer);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    help = app.help();
    return RunFlags{};
  } catch (const CLI::ParseError& e) {
    throw InputError(std::string(e.what()) + " (see " + spec.exe + " --help)");
  }

  // A flag given an empty value is refused, never taken as not given.
  for (CLI::Option* o : {o_integrator, o_out, o_stats, o_sweep}) {
    if (o && o->count() > 0 && o->as<std::string>().empty()) {
      throw flag_error(o->get_name(), "an empty value", "a non-empty value");
    }
  }
  for (CLI::Option* o : {o_integrators, o_dts}) {
    if (!o || o->count() == 0) continue;
    const auto items = o->as<std::vector<std::string>>();
    bool empty = items.empty();
    for (const auto& it : items) empty = empty || it.empty();
    if (empty) {
      throw flag_error(o->get_name(), "an empty entry", "a comma-separated list of values");
    }
  }
  if (dt_in) f.dt = parse_number("--dt", *dt_in, "a finite number > 0");
  if (f.dt && !(*f.dt > 0)) throw flag_error("--dt", num(*f.dt), "a finite number > 0");
  if (t_end_in) f.t_end = parse_number("--t-end", *t_end_in, "a finite number >= 0");
  if (f.t_end && !(*f.t_end >= 0)) {
    throw flag_error("--t-end", num(*f.t_end), "a finite number >= 0");
  }
  for (const auto& d : dts_in) {
    f.sweep_dts.push_back(parse_number("--dts", d, "finite step sizes > 0"));
  }
  if (steps_in) f.steps = long(parse_whole("--steps", *steps_in, 0, kMaxSteps));
  if (every_in) f.every = long(parse_whole("--every", *every_in, 1, INT64_MAX));
  if (seed_in) f.seed = std::uint64_t(parse_whole("--seed", *seed_in, 0, INT64_MAX));
  if (repeats_in) f.repeats = int(parse_whole("--repeats", *repeats_in, 1, 1000));
  // A flag the run would not read is refused, never ignored.
  if (every_in && f.out.empty() && f.stats.empty()) {
    throw flag_error("--every", "\"" + *every_in + "\" without --out or --stats",
                     "--every only beside an output it thins (--out, --stats)");
  }
  // The budget: CPU seconds and MiB, from a hundredth of a second up to a year, and
  // from 1 MiB up to a terabyte (docs/run-contract.md, "Limits").
  if (max_time_in) {
    const std::string expected = "a number of seconds from 0.01 to 31622400";
    f.max_time = parse_number("--max-time", *max_time_in, expected);
    if (!(*f.max_time >= 0.01 && *f.max_time <= 366.0 * 86400)) {
      throw flag_error("--max-time", "\"" + *max_time_in + "\"", expected);
    }
  }
  if (max_memory_in) {
    const std::string expected = "a number of MiB from 1 to 1048576";
    f.max_memory_mib = parse_number("--max-memory", *max_memory_in, expected);
    if (!(*f.max_memory_mib >= 1 && *f.max_memory_mib <= double(1 << 20))) {
      throw flag_error("--max-memory", "\"" + *max_memory_in + "\"", expected);
    }
  }
  if (!f.out.empty()) check_output_path("--out", f.out);
  if (!f.stats.empty()) check_output_path("--stats", f.stats);
  if (!f.sweep_csv.empty()) check_output_path("--sweep", f.sweep_csv);
  check_distinct("--out", f.out, "--stats", f.stats);
  check_distinct("--scene", f.scene_file, "--out", f.out);
  check_distinct("--scene", f.scene_file, "--stats", f.stats);
  check_distinct("--scene", f.scene_file, "--sweep", f.sweep_csv);
  return f;
}

std::optional<RunFlags> parse_run_flags(int argc, char** argv, const FlagSpec& spec,
                                        int& status) {
  std::string help;
  try {
    RunFlags f = read_run_flags(argc, argv, spec, help);
    if (!help.empty()) {
      std::cout << help;
      status = 0;
      return std::nullopt;
    }
    status = 0;
    return f;
  } catch (const InputError& e) {
    say(spec.exe, "error", e.what());
    status = 2;
    return std::nullopt;
  }
}

double step_size(const RunFlags& flags, std::optional<double> scene_dt,
                 const std::string& scene_file) {
  if (flags.dt) return *flags.dt;
  if (scene_dt) return *scene_dt;
  throw InputError(scene_file + ": dt: missing, expected a number > 0 (or pass --dt)");
}

long steps_to_take(const RunFlags& flags, std::optional<double> scene_t_end,
                   const std::string& scene_file, double h) {
  if (flags.steps) return *flags.steps;
  const double T = flags.t_end ? *flags.t_end : scene_t_end.value_or(-1.0);
  if (!(T >= 0)) {
    throw InputError(scene_file +
                     ": t_end: missing, expected a number >= 0 (or pass --steps or --t-end)");
  }
  const double n = std::round(T / h);
  if (!(n <= double(kMaxSteps))) {
    throw InputError(std::string(flags.t_end ? "--t-end" : scene_file + ": t_end") + " / " +
                     (flags.dt ? "--dt" : "dt") + ": got " + num(T) + " / " + num(h) +
                     ", which is " + num(n) + " steps, expected at most " +
                     std::to_string(kMaxSteps) + " steps");
  }
  return long(n);
}

std::string help_scenes_and_docs(const std::string& lab) {
  std::string s = "\nDefault scenes:\n";
  const auto scenes = default_scenes(lab);
  if (scenes.empty()) s += "  (none found under scenes/" + lab + ")\n";
  for (const auto& f : scenes) s += "  " + f + "\n";
  s += "\nThe last line on stdout is a JSON summary. Bad input exits with status 2.\n"
       "Scene keys: docs/scenes.md. Run contract: docs/run-contract.md.\n";
  return s;
}

}  // namespace wb
