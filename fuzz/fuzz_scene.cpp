// libFuzzer target: any bytes as a scene file, through everything a run does
// before its first step (issue 11; fuzz/README.md).
//   JSON parsing (depth, duplicate keys, number overflow) -> load_scene's
//   checks -> the forces glue (build_forces) -> the initial-state check ->
//   the sweep's "exact" reader and its closed form.
// It also feeds the input's first line to the whole-number flag parser.
// A finding is a crash, a sanitizer report, an exception other than
// InputError, an InputError message that is not one line of valid UTF-8, or
// a scene accepted with a non-finite state or a non-finite closed form.
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
#include "wb/run.h"
#include "wb/scene.h"
#include "wb/sweep.h"

namespace {

// Particles above which an input is skipped: the all-pairs forces would make
// one input take seconds (the limits themselves are tested in tests/badinput).
constexpr double kFuzzMaxParticles = 2000;

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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
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
    wb::ForceWorld world(scene);
    wb::check_initial_state(scene, world);
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
  } catch (const wb::InputError& e) {
    check_message(e.what(), wb::kMaxMessageBytes);
  }
  return 0;
}
