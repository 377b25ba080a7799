// libFuzzer target: any bytes as a collisions-lab scene file, through
// everything its executable does before the first step, then a few steps
// (fuzz/README.md).
//   JSON parsing -> wb::scene_from_json with the lab's keys (planes,
//   contact) -> the World (forces; planes, contact settings and the work
//   limits) -> the initial state check -> 3 steps of semi-implicit Euler,
//   each followed by the collision phase (broad phase, C1-C4 of the
//   solution, continuous check, shock propagation).
// A finding is a crash, a sanitizer report (a NaN cast to an integer in the
// broad phase among them), an exception other than InputError, a message
// that is not one line of valid UTF-8 of at most 1000 bytes, an accepted
// scene with a non-finite particle, or a plane normal that is not a unit
// vector.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "contact_world.h"
#include "declared_particles.h"
#include "fuzz_checks.h"
#include "wb/input.h"
#include "wb/run.h"
#include "wb/scene.h"
#include "wb/semi_implicit.h"

namespace {

constexpr double kFuzzMaxParticles = 2000;
constexpr int kFuzzSteps = 3;
// The cost model's estimate of the steps (an optimised build's CPU time) above
// which an accepted scene is not stepped.
constexpr double kFuzzMaxSeconds = 2e-3;
constexpr double kFuzzDefaultDt = 1e-2;

constexpr const char* kFuzzTarget = "fuzz_collisions_scene";

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
    wb::Scene scene =
        wb::scene_from_json("fuzz.json", std::move(doc), std::nullopt, {"planes", "contact"});
    wb::check_particles(scene, "the fuzzer");
    wb::ContactWorld world(scene);
    for (std::size_t k = 0; k < world.planes().size(); ++k) {
      const wb::PlaneDef& p = world.planes()[k];
      if (!(std::abs(p.n.norm() - 1.0) <= 1e-12) || !p.point.allFinite()) {
        finding("accepted a plane with a non-unit normal", std::to_string(k));
      }
    }
    wb::check_initial_state(scene, world);
    wb::StepCost cost;
    wb::contact_step_cost(scene, wb::semi_implicit_euler_integrator(), cost);
    if (fuzzcheck::too_slow(cost, kFuzzSteps, kFuzzMaxSeconds)) return 0;
    wb::Mat2X a(2, scene.n());
    world.dynamics().acceleration(scene.x, scene.v, a);
    if (!a.allFinite())
      finding("accepted a scene whose initial accelerations are not finite", "");
    const double h = scene.dt.value_or(kFuzzDefaultDt);
    wb::Mat2X x = scene.x, v = scene.v;
    wb::Scratch s;
    s.resize(scene.n());
    for (int k = 0; k < kFuzzSteps; ++k) {
      wb::semi_implicit_euler_step(world.dynamics(), h, x, v, s);
      world.after_step(h, x, v);
    }
    (void)world.energy(x, v);
  } catch (const wb::InputError& e) {
    fuzzcheck::check_message(kFuzzTarget, e.what(), wb::kMaxMessageBytes);
  }
  return 0;
}
