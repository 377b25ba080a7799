// Diagnosis probes of F8 (tests/common/wb_probe.h): the flow alone (inside and outside a core
// off the origin), the drag (between two particles that move with the flow, so feel nothing:
// a loop that skips the first or the last does not show there), every particle, what f held.
#include "vortex.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_F8_vortex {

using wbprobe::cols;

namespace {
using wb::Vec2;
VortexParams vortex(Vec2 c, double omega, double core, double drag) {
  VortexParams p;
  p.center = c, p.omega = omega, p.core = core, p.drag = drag;
  return p;
}
void in(wbprobe::Probe& P, const VortexParams& p) {
  P.in("center", p.center), P.in("omega", p.omega), P.in("core", p.core), P.in("drag", p.drag);
}
void flow(wbprobe::Probe& P, const Vec2& x, const VortexParams& p) {
  P.call("vortex_flow");
  P.in("x", x), in(P, p);
  P.out("returned", vortex_flow(x, p));
}
void drag(wbprobe::Probe& P, const wb::Mat2X& x, const wb::Mat2X& v, const VortexParams& p,
          wb::Mat2X f) {
  P.call("add_vortex");
  P.in("x", x), P.in("v", v), in(P, p), P.in("f", f);
  add_vortex(x, v, p, f);
  P.out("f", f);
}
const VortexParams kVortex = vortex(Vec2(1, -1), 0.8, 2.5, 1.5);
}  // namespace

WB_PROBE("F8", "flow-core",
         "vortex_flow inside the core: r = 0.5, core 1, omega 1, centre at the origin") {
  P.simple();
  flow(P, Vec2(0.5, 0), vortex(Vec2(0, 0), 1, 1, 1));
}
WB_PROBE("F8", "flow-outside",
         "vortex_flow outside the core: r = 2, core 1, omega 1, centre at the origin") {
  P.simple();
  flow(P, Vec2(0, 2), vortex(Vec2(0, 0), 1, 1, 1));
}
// The flow.
WB_PROBE("F8", "flow-in", "vortex_flow inside a core of radius 2.5 around (1, -1)") {
  flow(P, Vec2(2, 0), kVortex);
}
WB_PROBE("F8", "flow-out", "vortex_flow outside a core of radius 2.5 around (1, -1)") {
  flow(P, Vec2(4, 2), kVortex);
}
// The drag: the first and last particles move with the flow (u(2, 0) = (-0.8, 0.8),
// u(4, 2) = (-5/6, 5/6)).
WB_PROBE("F8", "drag", "add_vortex: a particle at rest between two that move with the flow") {
  drag(P, cols({{2, 0}, {0.5, -2}, {4, 2}}), cols({{-0.8, 0.8}, {0, 0}, {-5.0 / 6, 5.0 / 6}}),
       kVortex, cols({{0, 0}, {0, 0}, {0, 0}}));
}
// Every particle, and what f held.
WB_PROBE("F8", "three", "add_vortex on three particles, f holding forces") {
  drag(P, cols({{2, 0}, {0.5, -2}, {4, 2}}), cols({{0.3, 0}, {1, 1}, {0.5, -0.5}}), kVortex,
       cols({{1, 0}, {0, 1}, {-1, 0}}));
}

}  // namespace probe_F8_vortex
