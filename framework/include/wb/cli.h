// The run contract's flags (docs/run-contract.md), parsed and checked in one
// place for every lab executable, particle or rigid. This is the only part of
// the workbook that includes CLI11 (framework/src/cli.cpp), so only one file
// pays for compiling it.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "wb/input.h"

namespace wb {

// What the flags said; a flag not given is empty. Whole numbers are already
// parsed strictly (parse_whole) and output paths checked (check_output_path).
struct RunFlags {
  std::string scene_file, integrator, out, stats;
  std::optional<double> dt, t_end;
  std::optional<long> steps, every;
  std::optional<std::uint64_t> seed;
  // Sweep mode (docs/sweep.md); sweep_csv is empty outside it.
  std::string sweep_csv;
  std::vector<std::string> sweep_integrators;
  std::vector<double> sweep_dts;
  std::optional<int> repeats;
  // The cost model (docs/scenes.md, "Cost"): the budget, and --estimate (print
  // the estimate, run nothing).
  std::optional<double> max_time, max_memory_mib;
  bool estimate = false;
};

// What one executable offers and how its --help reads.
struct FlagSpec {
  std::string exe;                           // "forces", "rigid-solution"
  std::string summary;                       // first line of --help
  std::string footer;                        // after the flags: integrators, scene keys, scenes
  std::string trace_columns, stats_columns;  // the CSV headers, for --out and --stats
  bool seed = false;                         // offers --seed
  bool sweep = false;                        // offers --sweep and its flags
  std::string sweep_help;                    // what --sweep does, one sentence
};

// Parses and checks argv: InputError naming the flag, the value and what was
// expected (a flag the chosen mode would not read is refused too: --dt beside
// --dts, --every without --out or --stats). After --help, `help` holds the text
// and the flags are empty. Writes nothing.
RunFlags read_run_flags(int argc, const char* const* argv, const FlagSpec& spec,
                        std::string& help);

// read_run_flags for main(): returns the flags; or, after --help (printed,
// status 0) or a bad flag (one line on stderr, status 2), sets `status` and
// returns nothing.
std::optional<RunFlags> parse_run_flags(int argc, char** argv, const FlagSpec& spec, int& status);

// The number of steps a run takes: --steps, else round(T / h) with T from
// --t-end or the scene's t_end (`scene_t_end`, read from `scene_file`).
// Throws InputError when there is neither, or beyond kMaxSteps.
long steps_to_take(const RunFlags& flags, std::optional<double> scene_t_end,
                   const std::string& scene_file, double h);

// The step size: --dt, else the scene's dt; InputError when neither is given.
double step_size(const RunFlags& flags, std::optional<double> scene_dt,
                 const std::string& scene_file);

// The named entry of a list of integrators (anything with a `name`), or
// InputError naming `where`, the name given and the known names.
template <class Named>
const Named& find_named(const std::vector<Named>& list, const std::string& name,
                        const std::string& where);

// The integrator a run uses: --integrator, else the scene's "integrator"
// (`scene_integrator`, read from `scene_file`), else the list's first.
template <class Named>
const Named& choose_integrator(const std::vector<Named>& list, const RunFlags& flags,
                               const std::optional<std::string>& scene_integrator,
                               const std::string& scene_file);

// The --help tail every lab shares: its default scenes and where the contract
// and the scene keys are documented.
std::string help_scenes_and_docs(const std::string& lab);

}  // namespace wb

template <class Named>
const Named& wb::find_named(const std::vector<Named>& list, const std::string& name,
                            const std::string& where) {
  std::string known;
  for (const Named& it : list) {
    if (it.name == name) return it;
    known += (known.empty() ? "" : ", ") + it.name;
  }
  throw InputError(where + ": got \"" + name + "\", expected one of: " + known);
}

template <class Named>
const Named& wb::choose_integrator(const std::vector<Named>& list, const RunFlags& flags,
                                   const std::optional<std::string>& scene_integrator,
                                   const std::string& scene_file) {
  if (!flags.integrator.empty()) return find_named(list, flags.integrator, "--integrator");
  if (scene_integrator) return find_named(list, *scene_integrator, scene_file + ": integrator");
  return list.front();
}
