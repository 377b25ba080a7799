// Diagnosis probes of F2 (tests/common/wb_probe.h). "sum" is the total force: zero by
// Newton's third law.
#include "newton_gravity.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_F2_newton_gravity {

using wbprobe::cols;
using wbprobe::vec;

namespace {
void run(wbprobe::Probe& P, const wb::Mat2X& x, const wb::VecX& m, double G, double eps,
         wb::Mat2X f, bool each = false, bool sum_apart = false) {
  P.call("add_newton_gravity");
  P.in("x", x), P.in("m", m), P.in("G", G), P.in("eps", eps), P.in("f", f);
  const wb::Mat2X f0 = f;
  add_newton_gravity(x, m, G, eps, f);
  if (each) {
    P.out_each("f", f);
  } else {
    P.group("f");  // the forces and their sum go wrong together
    P.out("f", f);
  }
  if (sum_apart) P.group("");
  if (f.cols() == f0.cols()) P.out("sum", wb::Vec2((f - f0).rowwise().sum()));
  P.group("");
}
}  // namespace

WB_PROBE("F2", "unit-pair", "two unit masses 1 apart, G = 1, no softening") {
  P.simple();
  run(P, cols({{0, 0}, {1, 0}}), vec({1, 1}), 1.0, 0.0, cols({{0, 0}, {0, 0}}));
}
WB_PROBE("F2", "masses", "masses 1 and 3, 1 apart, G = 1, no softening") {
  P.simple();
  run(P, cols({{0, 0}, {1, 0}}), vec({1, 3}), 1.0, 0.0, cols({{0, 0}, {0, 0}}));
}
// The pair force, no softening.
WB_PROBE("F2", "pair", "masses 2 and 3 at distance 5, G = 0.8, no softening") {
  run(P, cols({{0, 0}, {3, 4}}), vec({2, 3}), 0.8, 0.0, cols({{0, 0}, {0, 0}}));
}
// The pair loop: two equal masses at distance 1, where a pair force with the wrong power of the
// distance or one body's mass twice is still right, while a pair visited twice, skipped, applied
// to one body or paired with itself is not. The sum apart: a force on one body only shows there.
WB_PROBE("F2", "unit-distance",
         "masses 2 and 2 at distance 1, at (0.5, 1.5) and (1.1, 2.3), G = 0.8, no softening") {
  run(P, cols({{0.5, 1.5}, {1.1, 2.3}}), vec({2, 2}), 0.8, 0.0, cols({{0, 0}, {0, 0}}), false,
      true);
}
// The softening.
WB_PROBE("F2", "softened", "the same pair softened by eps = 1.5") {
  run(P, cols({{0, 0}, {3, 4}}), vec({2, 3}), 0.8, 1.5, cols({{0, 0}, {0, 0}}));
}
// Every pair of several bodies.
WB_PROBE("F2", "four", "four bodies of different masses, no softening") {
  run(P, cols({{0, 0}, {3, 4}, {-1, 2}, {2, -1.5}}), vec({2, 3, 1.5, 0.5}), 0.8, 0.0,
      cols({{0, 0}, {0, 0}, {0, 0}, {0, 0}}));
}
// The pairs: three equal bodies equally spaced on a line. The middle one feels nothing from a
// pair force of any form, as long as every pair is visited once and acts on both bodies.
WB_PROBE("F2", "symmetric",
         "three bodies of mass 2 at (-1.5, 0.5), (0.5, 1), (2.5, 1.5): the middle one feels no "
         "force") {
  run(P, cols({{-1.5, 0.5}, {0.5, 1}, {2.5, 1.5}}), vec({2, 2, 2}), 0.8, 0.0,
      cols({{0, 0}, {0, 0}, {0, 0}}), true);
}
// A coincident pair without softening.
WB_PROBE("F2", "coincident", "two bodies at the same point and a third 2 away, no softening") {
  run(P, cols({{1, 1}, {1, 1}, {1, 3}}), vec({1, 2, 1.5}), 0.8, 0.0,
      cols({{0, 0}, {0, 0}, {0, 0}}));
}
// Adding to what f holds.
WB_PROBE("F2", "adds", "the pair of masses 2 and 3 with f already holding forces") {
  run(P, cols({{0, 0}, {3, 4}}), vec({2, 3}), 0.8, 0.0, cols({{1, 2}, {-3, 0.5}}));
}

}  // namespace probe_F2_newton_gravity
