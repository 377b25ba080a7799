// One main() for every lab (wb/lab.h): flags, the cost model, outputs, warnings,
// the run or the sweep, the summary line.
#include "wb/lab.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include "wb/budget.h"

namespace wb {

namespace {

FlagSpec flag_spec(const LabSpec& spec) {
  FlagSpec f;
  f.exe = spec.exe();
  f.summary = spec.summary;
  std::string footer = integrators_help(spec.integrators);
  for (const auto& section : spec.help_sections) footer += "\n" + section;
  if (spec.sweep) footer += sweep_help(spec.sweep_errors);
  f.footer = footer + budget_help() + help_scenes_and_docs(spec.lab);
  f.trace_columns = spec.trace_columns;
  f.stats_columns = spec.stats_columns;
  f.seed = spec.seed;
  f.sweep = spec.sweep;
  f.sweep_help =
      "Sweep mode: run the integrators over a ladder of step sizes (default dt*2^k, "
      "k = 3..-6) to t_end" +
      (spec.sweep_scenes.empty() ? "" : " " + spec.sweep_scenes) +
      " and write one CSV row per run";
  return f;
}

// The start of a process and the scene file it parsed.
void add_start(Estimate& e, const std::string& scene_file) {
  e.add("start: the process and its libraries", "", 1, kStartSeconds, kBaseBytes);
  std::error_code ec;
  const auto size = std::filesystem::file_size(scene_file, ec);
  const double bytes = ec ? 0.0 : double(size);
  e.add("scene file: " + std::to_string(std::uint64_t(bytes)) + " bytes parsed", "--scene", bytes,
        kSecondsPerFileByte, kBytesPerFileByte * bytes);
}

std::string times_text(double n, const char* what) {
  return " x " + std::to_string(std::uint64_t(n)) + " " + what;
}

std::size_t index_of(const std::vector<IntegratorLine>& list, const IntegratorLine& it) {
  return std::size_t(&it - list.data());
}

// Prints the estimate (--estimate) with what the budget says of it.
void print_estimate(const Estimate& e, const Budget& b, const std::string& file) {
  ordered_json j = estimate_json(e);
  try {
    const std::string w = judge(e, b, file);
    j["verdict"] = w.empty() ? "runs" : "warns";
  } catch (const InputError& err) {
    j["verdict"] = "refused";
    j["refusal"] = err.what();
  }
  print_summary(j);
}

}  // namespace

Estimate run_estimate(const LabScene& s, const RunRequest& r, bool outputs,
                      const std::string& scene_file) {
  Estimate e;
  add_start(e, scene_file);
  StepCost c;
  s.cost(r.integrator, c);
  e.add_times(c.once, 1, "");
  e.add_times(c.step, double(r.steps), times_text(double(r.steps), "steps"));
  if (outputs) {
    const double written = double(r.steps / std::max(1L, r.every)) + 2;
    e.add_times(c.record, written, times_text(written, "written steps"));
  }
  return e;
}

Estimate sweep_estimate(const LabScene& s, const SweepPlan& plan, int repeats,
                        const std::string& scene_file) {
  Estimate e;
  add_start(e, scene_file);
  double steps = 0;  // every run of one integrator: an untimed run and `repeats` timed ones
  for (long n : plan.steps) steps += double(n) * double(1 + repeats);
  // The integrators' runs follow one another: the one that holds the most memory
  // while it runs sets the sweep's peak.
  std::vector<StepCost> costs(plan.integrators.size());
  std::size_t peak = 0;
  for (std::size_t k = 0; k < costs.size(); ++k) {
    s.cost(plan.integrators[k], costs[k]);
    if (costs[k].step.bytes() > costs[peak].step.bytes()) peak = k;
  }
  // What is built once: the first integrator's, and what another adds (an analysis).
  std::set<std::string> built;
  for (std::size_t k = 0; k < costs.size(); ++k) {
    Estimate once;
    for (const CostTerm& t : costs[k].once.terms()) {
      if (built.insert(t.what).second) once.add(t.what, t.key, 1, t.seconds, t.bytes);
    }
    e.add_times(once, 1, "");
    e.add_times(costs[k].step, steps,
                times_text(steps, "steps") + " (" + std::to_string(plan.dts.size()) +
                    " step sizes, each run 1 + " + std::to_string(repeats) + " times)",
                k == peak);
  }
  s.sweep_cost(plan, e);
  return e;
}

int run_lab(int argc, char** argv, const LabSpec& spec, const LabLoader& load) {
  const FlagSpec fs = flag_spec(spec);
  int status = 0;
  const std::optional<RunFlags> flags = parse_run_flags(argc, argv, fs, status);
  if (!flags) return status;
  const std::string& exe = fs.exe;

  return guarded_main(exe, [&] {
    Budget budget;
    if (flags->max_time) budget.seconds = *flags->max_time;
    if (flags->max_memory_mib) budget.bytes = *flags->max_memory_mib * 1024.0 * 1024.0;
    // The wall: from here on the process's CPU time and memory are measured (wb/budget.h),
    // the scene's loading included; the estimate below refuses before the first step.
    budget::start({budget.seconds, budget.bytes}, exe, flags->scene_file);
    budget::PhaseScope loading(budget::kLoad);
    std::unique_ptr<LabScene> s = load(*flags);
    s->exe = exe;
    std::vector<std::string> names;
    for (const IntegratorLine& it : spec.integrators) names.push_back(it.name);

    if (!flags->sweep_csv.empty()) {
      const int repeats = flags->repeats.value_or(3);
      const SweepPlan plan =
          plan_sweep(names, flags->sweep_integrators, flags->sweep_dts, flags->dt, flags->t_end,
                     s->dt, s->t_end, s->file, repeats);
      const Estimate e = sweep_estimate(*s, plan, repeats, flags->scene_file);
      if (flags->estimate) {
        budget::finish();
        print_estimate(e, budget, s->file);
        return 0;
      }
      std::vector<std::string> warnings;
      const std::string w = judge(e, budget, s->file);
      if (!w.empty()) warnings.push_back(w);
      // Every integrator's runs (an untimed one and `repeats` timed ones per step
      // size), and the reference, run once.
      double runs = 0;
      for (long n : plan.steps) runs += double(n) * double(1 + repeats);
      budget::plan(runs * double(plan.integrators.size()) + s->reference_steps(plan));
      budget::PhaseScope preparing(budget::kPrepare);
      for (const std::string& x : s->prepare(plan.integrators, &plan)) warnings.push_back(x);
      CsvFile csv(flags->sweep_csv, sweep_columns() + "\n", "--sweep");
      for (const std::string& x : warnings) say(exe, "warning", x);
      budget::loop_started();
      const std::vector<SweepRow> rows = sweep_rows(plan, names, s->sweep_hooks(), exe, repeats);
      budget::PhaseScope writing(budget::kOutput);
      csv.rows() += sweep_table(s->name, names, rows, false);
      csv.commit();
      budget::finish();
      print_summary(sweep_summary(flags->sweep_csv, rows));
      return 0;
    }

    RunRequest r;
    r.integrator = index_of(spec.integrators,
                            choose_integrator(spec.integrators, *flags, s->integrator, s->file));
    r.dt = step_size(*flags, s->dt, s->file);
    r.steps = steps_to_take(*flags, s->t_end, s->file, r.dt);
    r.every = flags->every.value_or(1);
    const bool outputs = !flags->out.empty() || !flags->stats.empty();
    const Estimate e = run_estimate(*s, r, outputs, flags->scene_file);
    if (flags->estimate) {
      budget::finish();
      print_estimate(e, budget, s->file);
      return 0;
    }
    std::vector<std::string> warnings;
    const std::string w = judge(e, budget, s->file);
    if (!w.empty()) warnings.push_back(w);
    budget::plan(double(r.steps));
    budget::PhaseScope preparing(budget::kPrepare);
    for (const std::string& x : s->prepare({r.integrator}, nullptr)) warnings.push_back(x);
    RunFiles files(flags->out, spec.trace_columns + "\n", flags->stats,
                   spec.stats_columns + "\n");
    // Accepted: what will be slow is said now, once, before the run.
    for (const std::string& x : warnings) say(exe, "warning", x);
    const Summary sum = s->run(r, files);
    budget::finish();
    for (const std::string& x : sum.warnings) say(exe, "warning", x);
    print_summary(summary_json(sum));
    return 0;
  });
}

}  // namespace wb
