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

[[noreturn]] void finding(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_rigid_scene: %s: %s\n", what, detail.c_str());
  std::abort();
}

// An independent check of UTF-8 (not the one the library uses).
bool valid_utf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const unsigned c = static_cast<unsigned char>(s[i]);
    const std::size_t n = c < 0x80           ? 1
                          : (c >> 5) == 0x6  ? 2
                          : (c >> 4) == 0xE  ? 3
                          : (c >> 3) == 0x1E ? 4
                                             : 0;
    if (n == 0 || i + n > s.size()) return false;
    std::uint32_t cp = n == 1 ? c : n == 2 ? (c & 0x1F) : n == 3 ? (c & 0x0F) : (c & 0x07);
    for (std::size_t k = 1; k < n; ++k) {
      const unsigned d = static_cast<unsigned char>(s[i + k]);
      if ((d >> 6) != 0x2) return false;
      cp = (cp << 6) | (d & 0x3F);
    }
    const std::uint32_t min_cp[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < min_cp[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += n;
  }
  return true;
}

// One line, valid UTF-8, bounded: what every message must be.
void check_message(const std::string& m) {
  if (m.size() > wb::kMaxMessageBytes) {
    finding("message too long", std::to_string(m.size()) + " bytes");
  }
  if (!valid_utf8(m)) finding("message is not valid UTF-8", m);
  for (unsigned char c : m) {
    if (c < 0x20 || c == 0x7F) finding("message holds a control character", m);
  }
  if (m.find("\xC2\x85") != std::string::npos || m.find("\xE2\x80\xA8") != std::string::npos ||
      m.find("\xE2\x80\xA9") != std::string::npos) {
    finding("message holds a Unicode line break", m);
  }
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
