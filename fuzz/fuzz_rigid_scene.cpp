// libFuzzer target: any bytes as a rigid-lab scene file, through the rigid
// loader and a few steps (fuzz/README.md).
//   JSON parsing (depth, duplicate keys, number overflow) ->
//   rigid::scene_from_json's checks -> checks on what it accepted ->
//   5 steps of rigid::step with the first integrator (forces, hinges, contacts).
// A finding is a crash, a sanitizer report, an exception other than
// InputError, an InputError message that is not one line of valid UTF-8 of at
// most 1000 bytes, or an accepted scene whose initial state is not finite
// (x, v, omega, 1/m, the totals), whose orientations are not unit quaternions
// or whose plane normals are not unit vectors. A state that is not finite
// after the steps is not a finding (a scene may diverge); a sanitizer report
// on the way is.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "fuzz_checks.h"
#include "integrate_velocity.h"
#include "rigid_world.h"
#include "wb/input.h"

namespace {

// Bodies above which an input is skipped: the loader's cost is linear in the
// bodies, so more only slow the fuzzer down.
constexpr std::size_t kFuzzMaxBodies = 100;
// Steps taken on an accepted scene, and the step size when it has no dt.
constexpr int kFuzzSteps = 5;
constexpr double kFuzzDefaultDt = 1e-3;

constexpr const char* kFuzzTarget = "fuzz_rigid_scene";

[[noreturn]] void finding(const char* what, const std::string& detail) {
  fuzzcheck::finding(kFuzzTarget, what, detail);
}

void check_message(const std::string& m) {
  fuzzcheck::check_message(kFuzzTarget, m, wb::kMaxMessageBytes);
}

std::size_t declared_bodies(const wb::json& doc) {
  if (!doc.is_object()) return 0;
  auto b = doc.find("bodies");
  return b != doc.end() && b->is_array() ? b->size() : 0;
}

// What every accepted scene must satisfy before its first step.
void check_scene(const rigid::Scene& s) {
  std::vector<rigid::Body> bodies;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const rigid::Body& b = s.bodies[i].body;
    const std::string id = "body " + std::to_string(i);
    if (!b.x.allFinite() || !b.v.allFinite() || !b.omega.allFinite() ||
        !b.q.coeffs().allFinite()) {
      finding("accepted a non-finite body", id);
    }
    if (!(std::abs(b.q.norm() - 1.0) <= 1e-12)) finding("accepted a non-unit quaternion", id);
    if (!(b.m > 0) || !std::isfinite(b.m) || !std::isfinite(1.0 / b.m)) {
      finding("accepted a mass whose inverse is not finite", id);
    }
    bodies.push_back(b);
  }
  for (std::size_t i = 0; i < s.planes.size(); ++i) {
    if (!(std::abs(s.planes[i].normal.norm() - 1.0) <= 1e-12) || !s.planes[i].point.allFinite()) {
      finding("accepted a plane with a non-unit normal", std::to_string(i));
    }
  }
  for (std::size_t i = 0; i < s.hinges.size(); ++i) {
    if (!s.hinges[i].r_body.allFinite() || !s.hinges[i].anchor.allFinite()) {
      finding("accepted a hinge whose body point is not finite", std::to_string(i));
    }
  }
  if (!s.g.allFinite()) finding("accepted a non-finite gravity", "g");
  // The totals with the inertia the linked side computes (the solution's in
  // tools/fuzz's build).
  const rigid::Totals t = rigid::totals(s, bodies);
  if (!std::isfinite(t.kinetic) || !std::isfinite(t.potential) || !std::isfinite(t.energy()) ||
      !t.p.allFinite() || !t.L.allFinite()) {
    finding(
        "accepted a scene whose initial totals are not finite",
        "kinetic " + std::to_string(t.kinetic) + ", potential " + std::to_string(t.potential));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const wb::json doc = wb::parse_json(text, "fuzz.json");
    if (declared_bodies(doc) > kFuzzMaxBodies) return 0;
    const rigid::Scene scene = rigid::scene_from_json("fuzz.json", doc);
    check_scene(scene);
    wb::StepCost cost;
    rigid::step_cost(scene, cost);
    if (fuzzcheck::too_slow(cost, kFuzzSteps, 2e-3)) return 0;
    const rigid::Integrator integ{"implicit-gyroscopic", integrate_velocity_implicit, ""};
    const double h = scene.dt.value_or(kFuzzDefaultDt);
    std::vector<rigid::Body> bodies;
    for (const rigid::BodyDef& d : scene.bodies) bodies.push_back(d.body);
    for (int k = 0; k < kFuzzSteps; ++k) rigid::step(scene, integ, h, bodies);
    (void)rigid::totals(scene, bodies);
  } catch (const wb::InputError& e) {
    check_message(e.what());
  }
  return 0;
}
