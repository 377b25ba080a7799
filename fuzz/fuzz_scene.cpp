// libFuzzer target: any bytes as a scene file, through everything a run does
// before its first step and a few steps after it (issue 11, issue 31;
// fuzz/README.md).
//   JSON parsing (depth, duplicate keys, number overflow and underflow) ->
//   load_scene's checks -> the forces glue (build_forces: curl noise's derived
//   numbers) -> the initial-state check (each term's force bound, energy,
//   momentum) -> the forces evaluated (the solution's, curl noise included) ->
//   the sweep's "exact" reader and a small sweep (plan, the particle labs'
//   sweep state and the contract's loop, semi-implicit Euler and RK4).
// It also feeds the input's first line to the whole-number flag parser.
// A finding is a crash, a sanitizer report, an exception other than
// InputError, an InputError message that is not one line of valid UTF-8, a
// scene accepted with a non-finite state, initial force or closed form, or a
// timeout (an input the cost model called cheap).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "declared_particles.h"
#include "forces_world.h"
#include "fuzz_checks.h"
#include "wb/input.h"
#include "wb/rk4.h"
#include "wb/run.h"
#include "wb/scene.h"
#include "wb/semi_implicit.h"
#include "wb/sweep.h"

namespace {

// Particles above which an input is skipped (the limits themselves are tested
// in tests/badinput), and the cost model's estimate (an optimised build's CPU
// time) above which it is loaded but not evaluated or swept.
constexpr double kFuzzMaxParticles = 2000;
constexpr double kFuzzMaxSeconds = 2e-3;

constexpr const char* kFuzzTarget = "fuzz_scene";

[[noreturn]] void finding(const char* what, const std::string& detail) {
  fuzzcheck::finding(kFuzzTarget, what, detail);
}

void check_message(const std::string& m, std::size_t max_bytes) {
  fuzzcheck::check_message(kFuzzTarget, m, max_bytes);
}

void check_scene(const wb::Scene& s) {
  for (Eigen::Index i = 0; i < s.n(); ++i) {
    if (!s.x.col(i).allFinite() || !s.v.col(i).allFinite() || !(s.m[i] > 0) ||
        !std::isfinite(1.0 / s.m[i]) || !(s.radius[i] >= 0) || !std::isfinite(s.radius[i])) {
      finding("accepted a non-finite particle", std::to_string(i));
    }
  }
}

// The whole-number flags' parser on the input's first line (cheap, so on
// every input): a value or a refusal, never overflow.
void check_flags(const std::string& text) {
  const std::string arg = text.substr(0, text.find('\n'));
  for (std::int64_t max : {std::int64_t(wb::kMaxSteps), std::int64_t(INT64_MAX)}) {
    try {
      const std::int64_t v = wb::parse_whole("--steps", arg, 0, max);
      if (v < 0 || v > max) finding("parse_whole out of range", arg);
    } catch (const wb::InputError& e) {
      check_message(e.what(), wb::kMaxMessageBytes);
    }
  }
}

// A sweep of a few steps per run: the plan (from the scene's dt and t_end), its
// checks, the particle labs' sweep state and the contract's loop.
void small_sweep(const wb::Scene& scene, const wb::ForceWorld& world, const wb::StepCost& cost) {
  wb::LabInfo info;
  info.integrators = {wb::semi_implicit_euler_integrator(), wb::rk4_integrator()};
  const std::vector<std::string> names = {info.integrators[0].name, info.integrators[1].name};
  const double dt = scene.dt.value_or(0.01);
  try {
    const wb::SweepPlan plan = wb::plan_sweep(names, {}, {dt, 2 * dt}, std::nullopt, 2 * dt,
                                              scene.dt, scene.t_end, scene.file, 1);
    const wb::ExactSolution exact = wb::read_exact(scene);
    double steps = 0;  // every run twice (untimed, timed), and the reference (rk4's cost)
    for (long n : plan.steps) steps += 2.0 * 2 * double(n);
    if (exact.kind == wb::ExactSolution::kNone) {
      for (const wb::ReferenceRun& r : wb::reference_runs(plan)) steps += double(r.steps);
    }
    if (fuzzcheck::too_slow(cost, steps, kFuzzMaxSeconds)) return;
    wb::check_sweep(scene, exact, plan, plan.ladder);
    wb::ParticleSweep sweep(info, scene, world, exact, plan, "fuzz");
    for (const wb::SweepRow& row : wb::sweep_rows(plan, names, sweep.hooks(), "fuzz", 1)) {
      if (row.steps < 1) finding("a sweep row without steps", std::to_string(row.steps));
    }
  } catch (const wb::InputError& e) {
    check_message(e.what(), wb::kMaxMessageBytes);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzzcheck::quiet();
  const std::string text(reinterpret_cast<const char*>(data), size);
  check_message(wb::one_line(text), wb::kMaxMessageBytes);
  check_flags(text);
  try {
    wb::json doc = wb::parse_json(text, "fuzz.json");
    check_message(wb::describe(doc), 80);
    const double total = fuzzcheck::declared_particles(doc);
    if (total > kFuzzMaxParticles && total <= double(wb::kMaxParticles)) return 0;
    wb::Scene scene =
        wb::scene_from_json("fuzz.json", std::move(doc), std::nullopt, wb::sweep_scene_keys());
    check_scene(scene);
    wb::check_particles(scene, "the fuzzer");
    // What the cost model says the checks and a few steps cost, before building.
    wb::StepCost cost;
    wb::forces_step_cost(scene, wb::rk4_integrator(), cost);
    if (fuzzcheck::too_slow(cost, 4, kFuzzMaxSeconds)) return 0;
    wb::ForceWorld world(scene);
    wb::check_initial_state(scene, world);
    // Accepted: the forces at the initial state (the solution's functions) are finite.
    wb::Mat2X a(2, scene.n());
    world.dynamics().acceleration(scene.x, scene.v, a);
    if (!a.allFinite())
      finding("accepted a scene whose initial accelerations are not finite", "");
    const wb::ExactSolution exact = wb::read_exact(scene);
    if (exact.kind != wb::ExactSolution::kNone) {
      const double T = scene.t_end.value_or(1.0);
      for (double t : {0.0, 0.1 * T, 0.5 * T, T}) {
        wb::Vec2 x, v;
        exact.at(t, x, v);
        if (!x.allFinite() || !v.allFinite()) {
          finding("accepted an exact motion that is not finite", "t = " + std::to_string(t));
        }
      }
    }
    small_sweep(scene, world, cost);
  } catch (const wb::InputError& e) {
    check_message(e.what(), wb::kMaxMessageBytes);
  }
  return 0;
}
