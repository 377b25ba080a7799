// Diagnosis probes of F3 (tests/common/wb_probe.h). A massless particle last feels no pull
// from a correct formula: it keeps a loop that skips the last particle out of the probes of
// the formula.
#include "attractor.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_F3_attractor {

using wbprobe::cols;
using wbprobe::vec;

namespace {
void run(wbprobe::Probe& P, const wb::Mat2X& x, const wb::VecX& m, const wb::Vec2& c, double GM,
         wb::Mat2X f) {
  P.call("add_attractor");
  P.in("x", x), P.in("m", m), P.in("center", c), P.in("GM", GM), P.in("f", f);
  add_attractor(x, m, c, GM, f);
  P.out("f", f);
}
}  // namespace

WB_PROBE("F3", "unit",
         "one particle of mass 1 at distance 1 on the x axis, centre at the origin") {
  P.simple();
  run(P, cols({{1, 0}}), vec({1}), wb::Vec2(0, 0), 1.0, cols({{0, 0}}));
}
WB_PROBE("F3", "distance", "one particle of mass 1 at distance 2, centre at the origin") {
  P.simple();
  run(P, cols({{0, 2}}), vec({1}), wb::Vec2(0, 0), 1.0, cols({{0, 0}}));
}
// The pull formula.
WB_PROBE("F3", "pull",
         "a particle of mass 2 at distance 5 from the centre (1, -3), a massless one") {
  run(P, cols({{4, 1}, {0, 3}}), vec({2, 0}), wb::Vec2(1, -3), 1.5, cols({{0, 0}, {0, 0}}));
}
// A particle on the centre.
WB_PROBE("F3", "on-centre", "a particle exactly on the centre (1, -3), a massless one") {
  run(P, cols({{1, -3}, {0, 3}}), vec({2, 0}), wb::Vec2(1, -3), 1.5, cols({{0, 0}, {0, 0}}));
}
// Every particle.
WB_PROBE("F3", "three", "three particles of different masses and distances") {
  run(P, cols({{4, 1}, {-1, 0}, {2, 2}}), vec({2, 0.5, 1.5}), wb::Vec2(1, -3), 1.5,
      cols({{0, 0}, {0, 0}, {0, 0}}));
}
// Adding to what f holds.
WB_PROBE("F3", "adds", "the particle of mass 2 and the massless one, f already holding forces") {
  run(P, cols({{4, 1}, {0, 3}}), vec({2, 0}), wb::Vec2(1, -3), 1.5, cols({{1, 2}, {-0.5, 1}}));
}

}  // namespace probe_F3_attractor
