// Diagnosis probes of F1 (tests/common/wb_probe.h).
#include "uniform_gravity.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_F1_uniform_gravity {

using wbprobe::cols;
using wbprobe::vec;

namespace {
void run(wbprobe::Probe& P, const wb::VecX& m, const wb::Vec2& g, wb::Mat2X f) {
  P.call("add_uniform_gravity");
  P.in("m", m), P.in("g", g), P.in("f", f);
  add_uniform_gravity(m, g, f);
  // Particle by particle: a loop that misses one leaves the others right, where a formula
  // mistake gets every one wrong.
  if (f.cols() > 1)
    P.out_each("f", f);
  else
    P.out("f", f);
}
}  // namespace

WB_PROBE("F1", "one", "one particle of mass 2, g straight down") {
  P.simple();
  run(P, vec({2}), wb::Vec2(0, -9.81), cols({{0, 0}}));
}
WB_PROBE("F1", "x-only", "one particle of mass 2, g along x only") {
  P.simple();
  run(P, vec({2}), wb::Vec2(4, 0), cols({{0, 0}}));
}
// The weight alone: f comes in zero.
WB_PROBE("F1", "weight", "three particles of different masses, a tilted g") {
  run(P, vec({1.5, 0.4, 3}), wb::Vec2(1.2, -3.5), cols({{0, 0}, {0, 0}, {0, 0}}));
}
// Adding to what f holds.
WB_PROBE("F1", "adds", "the same particles with f already holding other forces") {
  run(P, vec({1.5, 0.4, 3}), wb::Vec2(1.2, -3.5), cols({{0.5, -1}, {0, 2}, {-3, 0.25}}));
}

}  // namespace probe_F1_uniform_gravity
