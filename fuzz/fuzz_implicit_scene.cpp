// libFuzzer target: any bytes as an implicit-lab scene file, through
// everything its executable does before the first step, then a few steps
// (fuzz/README.md).
//   JSON parsing -> wb::scene_from_json with the lab's keys (pinned, rope,
//   cloth, newton, exact) -> the generators (expand_implicit_scene) -> the
//   World (forces, generated springs, pins, newton options) -> the initial
//   state check -> every integrator's check -> 2 steps of backward-euler and
//   of implicit-trapezoid with the solution's functions.
// A finding is a crash, a sanitizer report, an exception other than
// InputError, a message that is not one line of valid UTF-8 of at most 1000
// bytes, or an accepted scene with a non-finite particle.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "declared_particles.h"
#include "fuzz_checks.h"
#include "implicit_world.h"
#include "wb/input.h"
#include "wb/run.h"
#include "wb/scene.h"
#include "wb/sweep.h"

namespace {

// Particles (declared and generated) above which an input is skipped, and the
// cost model's estimate of the steps (an optimised build's CPU time, at the
// iteration caps) above which it is loaded but not stepped.
constexpr double kFuzzMaxParticles = 2000;
constexpr double kFuzzMaxSeconds = 2e-3;
constexpr int kFuzzSteps = 2;
constexpr double kFuzzDefaultDt = 1e-2;

constexpr const char* kFuzzTarget = "fuzz_implicit_scene";

[[noreturn]] void finding(const char* what, const std::string& detail) {
  fuzzcheck::finding(kFuzzTarget, what, detail);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzzcheck::quiet();
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    wb::json doc = wb::parse_json(text, "fuzz.json");
    if (fuzzcheck::declared_particles(doc) > kFuzzMaxParticles) return 0;
    std::vector<std::string> keys = wb::implicit_scene_keys();
    keys.insert(keys.end(), wb::sweep_scene_keys().begin(), wb::sweep_scene_keys().end());
    wb::Scene scene = wb::scene_from_json("fuzz.json", std::move(doc), std::nullopt, keys);
    wb::expand_implicit_scene(scene);
    wb::check_particles(scene, "the fuzzer");
    for (Eigen::Index i = 0; i < scene.n(); ++i) {
      if (!scene.x.col(i).allFinite() || !scene.v.col(i).allFinite() ||
          !std::isfinite(1.0 / scene.m[i])) {
        finding("accepted a non-finite particle", std::to_string(i));
      }
    }
    const wb::Integrator be{"backward-euler", wb::backward_euler_adapter, 1, 1, ""};
    const wb::Integrator tr{"implicit-trapezoid", wb::implicit_trapezoid_adapter, 1, 2, ""};
    const wb::Integrator be1{"backward-euler-1",        wb::backward_euler_1_adapter, 1, 1, "",
                             wb::backward_euler_1_check};
    // What the cost model says the steps cost, before anything is built.
    wb::StepCost cost_be, cost_tr;
    wb::implicit_step_cost(scene, be, cost_be);
    wb::implicit_step_cost(scene, tr, cost_tr);
    const bool step = !fuzzcheck::too_slow(cost_be, kFuzzSteps, kFuzzMaxSeconds / 2) &&
                      !fuzzcheck::too_slow(cost_tr, kFuzzSteps, kFuzzMaxSeconds / 2);
    wb::ImplicitWorld world(scene);
    wb::check_initial_state(scene, world);
    wb::read_exact(scene);
    try {
      be1.check(be1, world.dynamics());
    } catch (const wb::InputError& e) {
      fuzzcheck::check_message(kFuzzTarget, e.what(), wb::kMaxMessageBytes);
    }
    if (!step) return 0;
    // Accepted: the forces at the initial state (the solution's functions) are finite.
    wb::Mat2X a(2, scene.n());
    world.dynamics().acceleration(scene.x, scene.v, a);
    if (!a.allFinite())
      finding("accepted a scene whose initial accelerations are not finite", "");
    const double h = scene.dt.value_or(kFuzzDefaultDt);
    for (const wb::Integrator* integ : {&be, &tr}) {
      wb::Mat2X x = scene.x, v = scene.v;
      wb::Scratch s;
      s.resize(scene.n());
      for (int k = 0; k < kFuzzSteps; ++k) integ->step(world.dynamics(), h, x, v, s);
      (void)world.energy(x, v);
    }
  } catch (const wb::InputError& e) {
    fuzzcheck::check_message(kFuzzTarget, e.what(), wb::kMaxMessageBytes);
  }
  return 0;
}
