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

// Particles (declared and generated) above which an input is skipped, and
// above which it is loaded but not stepped: a scene may ask for 1000 Newton
// iterations per step, each a sparse factorisation (about 0.1 ms for 50
// particles under the sanitizers); the loader is linear.
constexpr double kFuzzMaxParticles = 2000;
constexpr Eigen::Index kFuzzMaxStepped = 50;
constexpr int kFuzzSteps = 2;
constexpr double kFuzzDefaultDt = 1e-2;

constexpr const char* kFuzzTarget = "fuzz_implicit_scene";

[[noreturn]] void finding(const char* what, const std::string& detail) {
  fuzzcheck::finding(kFuzzTarget, what, detail);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
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
    wb::ImplicitWorld world(scene);
    wb::check_initial_state(scene, world);
    wb::read_exact(scene);
    const wb::Integrator be{"backward-euler", wb::backward_euler_adapter, 1, 1, "",
                            wb::newton_check};
    const wb::Integrator tr{"implicit-trapezoid", wb::implicit_trapezoid_adapter, 1, 2, "",
                            wb::newton_check};
    const wb::Integrator be1{"backward-euler-1",        wb::backward_euler_1_adapter, 1, 1, "",
                             wb::backward_euler_1_check};
    try {
      be1.check(be1, world.dynamics());
    } catch (const wb::InputError& e) {
      fuzzcheck::check_message(kFuzzTarget, e.what(), wb::kMaxMessageBytes);
    }
    if (scene.n() > kFuzzMaxStepped) return 0;
    const double h = scene.dt.value_or(kFuzzDefaultDt);
    for (const wb::Integrator* integ : {&be, &tr}) {
      integ->check(*integ, world.dynamics());
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
