// The live pages' step, natively: a lab's scene stepped through the live layer
// (framework/live/) exactly as a live page steps it in WebAssembly, with the solution's
// code. tools/live-check --bench divides the page's figure by this one, measured in the
// same run (docs/benchmarks.md, "Live pages").
//
//   bench_live [Google Benchmark flags] [LAB/SCENE[/INTEGRATOR]:STEPS ...]
//
// Each benchmark, live/LAB/SCENE[/INTEGRATOR], times STEPS steps from the scene's start
// (a reset, then one call of STEPS steps, as the page's bench does); the counter
// ms_per_step is its time per step. The scene's own dt and integrator unless named.
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "live.h"
#include "wb/input.h"

// Each lab's main(), compiled with main renamed (bench/CMakeLists.txt): calling it
// registers the lab with the live layer, as a live page's first call does.
#define WB_LIVE_MAIN(lab) int wb_live_main_##lab(int, char**);
WB_BENCH_LIVE_LABS(WB_LIVE_MAIN)
#undef WB_LIVE_MAIN

namespace {

struct Case {
  std::string lab, scene, integrator;
  long steps = 100;
};

std::string read(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot read " + path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

const wb::live::LabEntry& lab_entry(const std::string& lab) {
  for (const auto& e : wb::live::labs()) {
    if (e.lab == lab) return e;
  }
  throw std::runtime_error("bench_live: no lab \"" + lab + "\" in this build");
}

void run_case(benchmark::State& state, const Case& c) {
  const std::string file = std::string(WB_BENCH_SCENES) + "/" + c.lab + "/" + c.scene + ".json";
  const std::string text = read(file);
  std::unique_ptr<wb::live::Sim> sim = lab_entry(c.lab).make();
  sim->load(file, text);
  if (!c.integrator.empty()) sim->set_integrator(c.integrator);
  const double h = wb::json::parse(text).value("dt", 0.01);
  for (auto _ : state) {
    state.PauseTiming();
    sim->reset();
    state.ResumeTiming();
    const long k = sim->step(h, c.steps);
    if (k != c.steps) {
      state.SkipWithError("the run stopped (diverged) before its steps");
      return;
    }
  }
  // CPU milliseconds per step (a rate over the CPU time, inverted).
  state.counters["ms_per_step"] =
      benchmark::Counter(double(c.steps) * double(state.iterations()) / 1e3,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

Case parse_case(const std::string& arg) {
  Case c;
  const auto colon = arg.rfind(':');
  std::string path = arg;
  if (colon != std::string::npos) {
    c.steps = std::stol(arg.substr(colon + 1));
    path = arg.substr(0, colon);
  }
  std::vector<std::string> parts;
  std::stringstream s(path);
  for (std::string p; std::getline(s, p, '/');) parts.push_back(p);
  if (parts.size() < 2 || parts.size() > 3 || c.steps < 1) {
    throw std::runtime_error("bench_live: got \"" + arg +
                             "\", expected LAB/SCENE[/INTEGRATOR]:STEPS");
  }
  c.lab = parts[0];
  c.scene = parts[1];
  if (parts.size() == 3) c.integrator = parts[2];
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  char name[] = "bench_live";
  char* args[] = {name, nullptr};
#define WB_LIVE_CALL(lab) wb_live_main_##lab(1, args);
  WB_BENCH_LIVE_LABS(WB_LIVE_CALL)
#undef WB_LIVE_CALL
  std::vector<Case> cases;
  try {
    for (int i = 1; i < argc; ++i) cases.push_back(parse_case(argv[i]));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  if (cases.empty()) {
    for (const char* a : {"forces/flock:500", "euler/oscillator/symplectic-euler:20000",
                          "collisions/pile:20", "rigid/dzhanibekov:20000"}) {
      cases.push_back(parse_case(a));
    }
  }
  for (const Case& c : cases) {
    std::string name = "live/" + c.lab + "/" + c.scene;
    if (!c.integrator.empty()) name += "/" + c.integrator;
    benchmark::RegisterBenchmark(name.c_str(), [c](benchmark::State& st) {
      run_case(st, c);
    })->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
