// Diagnosis probes of I1 (tests/common/wb_probe.h): the spring alone, the drag alone, both with
// an external force.
#include "backward_euler_spring.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_I1_backward_euler_spring {

namespace {
using wb::Vec2;
void run(wbprobe::Probe& P, double m, double k, double b, const Vec2& c, const Vec2& f_ext,
         double h, Vec2 x, Vec2 v) {
  P.call("backward_euler_spring_step");
  P.in("m", m), P.in("k", k), P.in("b", b), P.in("c", c), P.in("f_ext", f_ext), P.in("h", h);
  P.in("x", x), P.in("v", v);
  backward_euler_spring_step(m, k, b, c, f_ext, h, x, v);
  P.out("x", x), P.out("v", v);
}
}  // namespace

WB_PROBE("I1", "unit",
         "m = 1, k = 1, no drag, anchor at the origin, from x = (1, 0) at rest, h = 1") {
  P.simple();
  run(P, 1, 1, 0, Vec2(0, 0), Vec2(0, 0), 1, Vec2(1, 0), Vec2(0, 0));
}
// The spring alone.
WB_PROBE("I1", "spring", "the spring alone: m = 2, k = 50, anchor (1, -1), moving, h = 0.1") {
  P.simple();
  run(P, 2, 50, 0, Vec2(1, -1), Vec2(0, 0), 0.1, Vec2(1.5, 0.5), Vec2(0.3, -0.8));
}
// The drag alone.
WB_PROBE("I1", "drag", "the drag alone: m = 2, b = 30, no spring, moving, h = 0.1") {
  P.simple();
  run(P, 2, 0, 30, Vec2(1, -1), Vec2(0, 0), 0.1, Vec2(1.5, 0.5), Vec2(0.3, -0.8));
}
// Everything.
WB_PROBE("I1", "general", "spring, drag and an external force: m = 2, k = 50, b = 30, h = 0.1") {
  run(P, 2, 50, 30, Vec2(1, -1), Vec2(0.5, -19.6), 0.1, Vec2(1.5, 0.5), Vec2(0.3, -0.8));
}

}  // namespace probe_I1_backward_euler_spring
