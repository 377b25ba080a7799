// Diagnosis probes of F4 (tests/common/wb_probe.h).
#include "damping.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_F4_damping {

using wbprobe::cols;

namespace {
void run(wbprobe::Probe& P, const wb::Mat2X& v, double b, wb::Mat2X f) {
  P.call("add_damping");
  P.in("v", v), P.in("b", b), P.in("f", f);
  add_damping(v, b, f);
  // Particle by particle: a loop that misses one leaves the others right, where a formula
  // mistake gets every one wrong.
  if (f.cols() > 1)
    P.out_each("f", f);
  else
    P.out("f", f);
}
}  // namespace

WB_PROBE("F4", "x", "one particle moving along x, b = 1") {
  P.simple();
  run(P, cols({{1, 0}}), 1.0, cols({{0, 0}}));
}
// The drag.
WB_PROBE("F4", "drag", "three particles moving in different directions, b = 0.8") {
  run(P, cols({{1.5, -0.5}, {0, 2}, {-1, -1}}), 0.8, cols({{0, 0}, {0, 0}, {0, 0}}));
}
// Adding to what f holds.
WB_PROBE("F4", "adds", "the same particles with f already holding forces") {
  run(P, cols({{1.5, -0.5}, {0, 2}, {-1, -1}}), 0.8, cols({{1, 2}, {-0.5, 0}, {0, -3}}));
}

}  // namespace probe_F4_damping
