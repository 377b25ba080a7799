// libFuzzer target: any bytes as a command line (one argument per line), through
// the run contract's flags and what is planned from them (issue 31;
// fuzz/README.md).
//   read_run_flags (every flag, its value, the sets a mode refuses: --dt beside
//   --dts, --every without an output, --sweep beside --steps; output paths
//   checked, never opened) -> for a run: the integrator, the step, the steps;
//   for a sweep: plan_sweep -> a budget from --max-time and --max-memory
//   judging an estimate of the plan -> the estimate's JSON line.
// A finding is a crash, a sanitizer report, an exception other than InputError,
// a message that is not one line of valid UTF-8 of at most 1000 bytes, or a plan
// outside the documented limits (a step count outside 0 to 1e8, a step size
// that is not finite and positive).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_checks.h"
#include "wb/cli.h"
#include "wb/contract.h"
#include "wb/cost.h"
#include "wb/input.h"

namespace {

constexpr const char* kFuzzTarget = "fuzz_flags";
constexpr std::size_t kMaxArgs = 32;

[[noreturn]] void finding(const char* what, const std::string& detail) {
  fuzzcheck::finding(kFuzzTarget, what, detail);
}

void check_message(const std::string& m) {
  fuzzcheck::check_message(kFuzzTarget, m, wb::kMaxMessageBytes);
}

struct Named {
  std::string name;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzzcheck::quiet();
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> args = {"fuzz"};
  for (std::size_t b = 0; b <= text.size() && args.size() <= kMaxArgs;) {
    const std::size_t e = std::min(text.find('\n', b), text.size());
    args.push_back(text.substr(b, e - b));
    b = e + 1;
  }
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  wb::FlagSpec spec;
  spec.exe = "fuzz";
  spec.summary = "the fuzzer's flags";
  spec.trace_columns = "t,id";
  spec.stats_columns = "step,t";
  spec.seed = spec.sweep = true;
  spec.sweep_help = "sweep";
  const std::vector<Named> integrators = {{"a"}, {"b"}};
  const std::vector<std::string> names = {"a", "b"};
  const std::optional<double> scene_dt = 0.01, scene_t_end = 1.0;
  try {
    std::string help;
    const wb::RunFlags f = wb::read_run_flags(int(argv.size()), argv.data(), spec, help);
    if (!help.empty()) return 0;
    wb::Estimate e;
    if (!f.sweep_csv.empty()) {
      const wb::SweepPlan plan =
          wb::plan_sweep(names, f.sweep_integrators, f.sweep_dts, f.dt, f.t_end, scene_dt,
                         scene_t_end, "fuzz.json", f.repeats.value_or(3));
      for (std::size_t d = 0; d < plan.dts.size(); ++d) {
        if (!(plan.dts[d] > 0 && std::isfinite(plan.dts[d])) || plan.steps[d] < 1 ||
            plan.steps[d] > wb::kMaxSteps) {
          finding("a sweep plan outside the limits", std::to_string(plan.steps[d]));
        }
        e.add("runs", "--dts", double(plan.steps[d]), 1e-6);
      }
    } else {
      wb::choose_integrator(integrators, f, std::nullopt, "fuzz.json");
      const double h = wb::step_size(f, scene_dt, "fuzz.json");
      const long steps = wb::steps_to_take(f, scene_t_end, "fuzz.json", h);
      if (!(h > 0 && std::isfinite(h)) || steps < 0 || steps > wb::kMaxSteps) {
        finding("a run plan outside the limits", std::to_string(steps));
      }
      e.add("steps", "--steps", double(steps), 1e-6, 1e3);
    }
    wb::Budget b;
    if (f.max_time) b.seconds = *f.max_time;
    if (f.max_memory_mib) b.bytes = *f.max_memory_mib * 1024 * 1024;
    check_message(wb::judge(e, b, "fuzz.json"));
    (void)wb::estimate_json(e).dump();
  } catch (const wb::InputError& err) {
    check_message(err.what());
  }
  return 0;
}
