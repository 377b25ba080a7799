// Diagnosis probes of I2 (tests/common/wb_probe.h): a stretched spring, a compressed one with
// and without the clamp, ends at one point. f, K and D are recorded apart.
#include "spring_derivatives.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_I2_spring_derivatives {

namespace {
using wb::Vec2;
void run(wbprobe::Probe& P, const Vec2& xi, const Vec2& xj, const Vec2& vi, const Vec2& vj,
         double k, double rest, double kd, bool definite, bool together = false) {
  P.call("spring_derivatives");
  P.in("xi", xi), P.in("xj", xj), P.in("vi", vi), P.in("vj", vj), P.in("k", k);
  P.in("rest", rest), P.in("kd", kd), P.in("definite", definite);
  wb::Vec2 f(7, 7);
  wb::Mat2 K = wb::Mat2::Constant(7), D = wb::Mat2::Constant(7);
  spring_derivatives(xi, xj, vi, vj, k, rest, kd, definite, f, K, D);
  if (together) P.group("everything");  // where the ends coincide: f, K and D together
  P.out("f", f), P.out("K", K), P.out("D", D);
  P.group("");
}
}  // namespace

WB_PROBE("I2", "axis", "stretched along x: length 2, rest length 1, k = 1, ends at rest") {
  P.simple();
  run(P, Vec2(2, 0), Vec2(0, 0), Vec2(0, 0), Vec2(0, 0), 1, 1, 0, true);
}
// Stretched, tilted, moving.
WB_PROBE("I2", "stretched", "stretched and tilted: length 5, rest length 2, both ends moving") {
  run(P, Vec2(2, 1), Vec2(-1, -3), Vec2(0.5, 1), Vec2(-1, 0.25), 1.5, 2, 0.4, true);
}
// Compressed: the clamp matters.
WB_PROBE("I2", "compressed-exact", "compressed to half its rest length, definite = false") {
  run(P, Vec2(2, 1), Vec2(-1, -3), Vec2(0.5, 1), Vec2(-1, 0.25), 1.5, 10, 0.4, false);
}
WB_PROBE("I2", "compressed-clamped", "compressed to half its rest length, definite = true") {
  run(P, Vec2(2, 1), Vec2(-1, -3), Vec2(0.5, 1), Vec2(-1, 0.25), 1.5, 10, 0.4, true);
}
// No direction.
WB_PROBE("I2", "coincident", "both ends at one point, moving") {
  run(P, Vec2(1, 1), Vec2(1, 1), Vec2(0.5, 0), Vec2(0, -0.5), 2, 1, 0.5, true, true);
}

}  // namespace probe_I2_spring_derivatives
