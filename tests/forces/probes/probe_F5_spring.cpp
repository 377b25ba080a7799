// Diagnosis probes of F5 (tests/common/wb_probe.h): the spring alone (both ends at rest), the
// damper alone (at the rest length), both, a spring of zero length.
#include "spring.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_F5_spring {

namespace {
using wb::Vec2;
void run(wbprobe::Probe& P, const Vec2& xi, const Vec2& xj, const Vec2& vi, const Vec2& vj,
         double k, double rest, double kd) {
  P.call("spring_force");
  P.in("xi", xi), P.in("xj", xj), P.in("vi", vi), P.in("vj", vj), P.in("k", k);
  P.in("rest", rest), P.in("kd", kd);
  P.out("returned", spring_force(xi, xj, vi, vj, k, rest, kd));
}
}  // namespace

WB_PROBE("F5", "stretched", "ends at rest, stretched along x: length 2, rest length 1, k = 1") {
  P.simple();
  run(P, Vec2(2, 0), Vec2(0, 0), Vec2(0, 0), Vec2(0, 0), 1.0, 1.0, 0.0);
}
WB_PROBE("F5", "damper-along", "at the rest length, end i moving along the spring, kd = 0.5") {
  P.simple();
  run(P, Vec2(1, 0), Vec2(0, 0), Vec2(1, 0), Vec2(0, 0), 3.0, 1.0, 0.5);
}
WB_PROBE("F5", "damper-across", "at the rest length, end i moving across the spring: no force") {
  P.simple();
  run(P, Vec2(1, 0), Vec2(0, 0), Vec2(0, 1), Vec2(0, 0), 3.0, 1.0, 0.5);
}
// The spring term: both ends at rest.
WB_PROBE("F5", "spring", "ends at rest, length 5, rest length 2, k = 1.5") {
  run(P, Vec2(2, 1), Vec2(-1, -3), Vec2(0, 0), Vec2(0, 0), 1.5, 2.0, 0.4);
}
// The damper term: at the rest length, moving obliquely.
WB_PROBE("F5", "damper", "at the rest length 5, both ends moving obliquely, kd = 0.4") {
  run(P, Vec2(2, 1), Vec2(-1, -3), Vec2(0.5, 1), Vec2(-1, 0.25), 1.5, 5.0, 0.4);
}
// Both.
WB_PROBE("F5", "both", "stretched and moving: length 5, rest length 2") {
  run(P, Vec2(2, 1), Vec2(-1, -3), Vec2(0.5, 1), Vec2(-1, 0.25), 1.5, 2.0, 0.4);
}
// No direction.
WB_PROBE("F5", "zero-length", "both ends at the same point, moving") {
  run(P, Vec2(1, 1), Vec2(1, 1), Vec2(0.5, 0), Vec2(0, -0.5), 2.0, 1.0, 0.5);
}

}  // namespace probe_F5_spring
