// Diagnosis probes of F2 (tests/common/wb_probe.h). "sum" is the total force: zero by
// Newton's third law. The probes that tell parts apart have three bodies or more: with two, a
// loop that misses the last body does nothing, which no other pair-loop mistake does.
#include <cmath>

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
// The pair force, no softening (a detail: two bodies, where a loop that misses the last one does
// nothing at all).
WB_PROBE("F2", "pair", "masses 2 and 3 at distance 5, G = 0.8, no softening") {
  P.simple();
  run(P, cols({{0, 0}, {3, 4}}), vec({2, 3}), 0.8, 0.0, cols({{0, 0}, {0, 0}}));
}
// The pair loop: three equal masses 1 apart from each other (a unit triangle), where a pair force
// with the wrong power of the distance or one body's mass twice is still right, while a pair
// visited twice, skipped, applied to one body or paired with itself is not. The sum apart: a
// force on one body only shows there.
WB_PROBE("F2", "unit-distance",
         "masses 2, 2 and 2 at the corners of a triangle of side 1, (0.5, 1.5), (1.1, 2.3) and "
         "(0.8 - 0.4 sqrt 3, 1.9 + 0.3 sqrt 3), G = 0.8, no softening") {
  const double r3 = std::sqrt(3.0);
  run(P, cols({{0.5, 1.5}, {1.1, 2.3}, {0.8 - 0.4 * r3, 1.9 + 0.3 * r3}}), vec({2, 2, 2}), 0.8,
      0.0, cols({{0, 0}, {0, 0}, {0, 0}}), false, true);
}
// The softening: three bodies softened, and the same unsoftened in one output (a mistake that
// shows only without softening, a body paired with itself, shows with the others' here, while
// a softening mistake does not show at eps = 0).
WB_PROBE("F2", "softened",
         "masses 2, 3 and 1.5 at (0, 0), (3, 4) and (-1, 2), G = 0.8, softened by eps = 1.5, "
         "then eps = 0") {
  const wb::Mat2X x = cols({{0, 0}, {3, 4}, {-1, 2}});
  const wb::VecX m = vec({2, 3, 1.5});
  P.call("add_newton_gravity");
  P.in("x", x), P.in("m", m), P.in("G", 0.8), P.in("eps (then 0)", 1.5);
  wb::Mat2X f = wb::Mat2X::Zero(2, 3), f0 = wb::Mat2X::Zero(2, 3);
  add_newton_gravity(x, m, 0.8, 1.5, f);
  add_newton_gravity(x, m, 0.8, 0.0, f0);
  P.group("f");
  P.out("f (eps = 1.5)", f);
  P.out("f (eps = 0)", f0);
  P.group("");
}
// Every pair of several bodies, each body's force apart (a loop that misses the last body or
// applies a pair to one body only leaves the last body's force at 0).
WB_PROBE("F2", "four", "four bodies of different masses, no softening") {
  run(P, cols({{0, 0}, {3, 4}, {-1, 2}, {2, -1.5}}), vec({2, 3, 1.5, 0.5}), 0.8, 0.0,
      cols({{0, 0}, {0, 0}, {0, 0}, {0, 0}}), true);
}
// The pairs: three bodies equally spaced on a line, the outer two of equal mass. The middle one
// feels nothing from a pair force of any form, as long as every pair is visited once and acts on
// both bodies; its own mass is not the others', so that a body's mass taken for its partner's
// shows. The sum apart.
WB_PROBE("F2", "symmetric",
         "three bodies of masses 2, 3 and 2 at (-1.5, 0.5), (0.5, 1), (2.5, 1.5): the middle one "
         "feels no force") {
  run(P, cols({{-1.5, 0.5}, {0.5, 1}, {2.5, 1.5}}), vec({2, 3, 2}), 0.8, 0.0,
      cols({{0, 0}, {0, 0}, {0, 0}}), false, true);
}
// A coincident pair without softening.
// The coincident bodies first and last: a loop that skips the last body, or applies a pair to one
// body only, loses the same force here.
WB_PROBE("F2", "coincident",
         "two bodies at one point (first and last) and a third 2 from them, no softening") {
  run(P, cols({{1, 1}, {1, 3}, {1, 1}}), vec({1, 1.5, 2}), 0.8, 0.0,
      cols({{0, 0}, {0, 0}, {0, 0}}), true);
}
// Adding to what f holds (a detail, as "pair").
WB_PROBE("F2", "adds", "the pair of masses 2 and 3 with f already holding forces") {
  P.simple();
  run(P, cols({{0, 0}, {3, 4}}), vec({2, 3}), 0.8, 0.0, cols({{1, 2}, {-3, 0.5}}));
}

}  // namespace probe_F2_newton_gravity
