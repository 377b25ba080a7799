// Graded tests for C4, Coulomb friction (labs/collisions/friction_impulse.cpp).
// Expected values: Coulomb's law (the tangential impulse stops the sliding if
// that takes at most mu jn, else it is mu jn against the sliding), and the
// block on a slope of angle theta: at rest for tan theta <= mu, otherwise
// sliding with acceleration g (sin theta - mu cos theta).
#include <cmath>

#include "friction_impulse.h"
#include "heldout.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_C4_friction_impulse {

namespace {

using wb::Vec2;
using wbtest::require_near;

constexpr double kRound = 1e-13;  // a few ulps of O(1) quantities
const Vec2 kN(0.6, 0.8), kT(-0.8, 0.6);

// Slides a block on a slope of angle theta (plane through 0 with normal n) for
// `steps` steps of semi-implicit Euler: gravity, the normal impulse that
// cancels the approach (resting, e = 0), then friction. Returns the velocity.
Vec2 slide(double theta, double mu, int steps, double h, Vec2& x) {
  const double g = 9.81, m = 2.0;
  const Vec2 n(-std::sin(theta), std::cos(theta));
  Vec2 v(0, 0);
  for (int k = 0; k < steps; ++k) {
    v.y() -= g * h;
    const double vn = v.dot(n);
    if (vn < 0) {
      const double jn = -m * vn;
      v += (jn / m) * n;
      friction_impulse(n, jn, mu, m, v);
    }
    x += h * v;
  }
  return v;
}

}  // namespace

TEST_CASE("C4 friction_impulse: inside the friction cone the tangential velocity stops",
          "[collisions][C4][2pts]") {
  Vec2 v = -0.5 * kN + 0.2 * kT;
  const double jt = friction_impulse(kN, 3.0, 0.5, 2.0, v);  // needs 2 * 0.2 = 0.4 <= 1.5
  require_near(v, Vec2(-0.5 * kN), kRound, "static friction: tangential velocity 0, normal kept");
  require_near(jt, 0.4, kRound, "returned impulse m |v_t| = 2 * 0.2");
}

TEST_CASE("C4 friction_impulse: outside the cone the impulse is mu jn against the sliding",
          "[collisions][C4][2pts]") {
  Vec2 v = 0.1 * kN + 3.0 * kT;
  const double jt = friction_impulse(kN, 1.0, 0.4, 2.0, v);  // would need 6 > mu jn = 0.4
  require_near(v, Vec2(0.1 * kN + 2.8 * kT), kRound,
               "sliding: tangential speed drops by mu jn / m = 0.2, normal velocity kept");
  require_near(jt, 0.4, kRound, "returned impulse mu jn");
}

TEST_CASE("C4 friction_impulse: a block on a slope sticks when tan theta < mu",
          "[collisions][C4][2pts]") {
  const double theta = 20.0 * M_PI / 180.0;  // tan = 0.364 < 0.5
  Vec2 x(0.25, -0.5);
  const Vec2 v = slide(theta, 0.5, 2000, 1e-3, x);
  constexpr double kStickTol = 1e-12;  // rounding of the normal impulse each step
  require_near(v.norm(), 0.0, kStickTol, "speed of a block that static friction holds");
  require_near(x, Vec2(0.25, -0.5), 1e-12, "position of a block that static friction holds");
}

TEST_CASE(
    "C4 friction_impulse: on a steeper slope it slides with a = g (sin theta - mu cos "
    "theta)",
    "[collisions][C4][2pts]") {
  const double theta = 35.0 * M_PI / 180.0, mu = 0.3, g = 9.81, h = 1e-3;
  const int steps = 1000;
  Vec2 x(0, 0);
  const Vec2 v = slide(theta, mu, steps, h, x);
  const Vec2 down(-std::cos(theta), -std::sin(theta));  // down the slope
  // Each step: gravity adds g h (sin theta) along the slope and g h cos theta
  // into it; the normal impulse cancels the latter and friction removes mu times
  // it: the speed grows by exactly h g (sin - mu cos) per step (no step-size error).
  const double a = g * (std::sin(theta) - mu * std::cos(theta));
  require_near(v, Vec2(a * steps * h * down), 1e-10,
               "velocity after 1 s: a t down the slope (rounding over 1000 steps)");
}

TEST_CASE(
    "C4 friction_impulse: the impulse opposes the sliding in both directions and no sliding "
    "or mu jn = 0 gives no NaN",
    "[collisions][C4][2pts]") {
  for (double s : {1.0, -1.0}) {
    Vec2 v = -0.2 * kN + s * 1.5 * kT;
    friction_impulse(kN, 2.0, 0.25, 1.0, v);  // bound 0.5 < 1.5: sliding
    INFO("tangential direction " << s);
    require_near(v, Vec2(-0.2 * kN + s * 1.0 * kT), kRound, "speed 1.5 - mu jn / m = 1.0");
  }
  Vec2 v = -0.7 * kN;  // no tangential velocity
  const double jt = friction_impulse(kN, 2.0, 0.25, 1.0, v);
  wbtest::require_finite(wb::Mat2X(v), "velocity with no tangential part");
  require_near(v, Vec2(-0.7 * kN), kRound, "nothing to stop: velocity unchanged");
  require_near(jt, 0.0, kRound, "no tangential impulse");
  // jn = 0 (no contact this step) or mu = 0 (ice): the cone is the point 0, so the
  // tangential impulse is 0, with or without sliding (v_t = 0 included: no 0 / 0).
  for (double vt : {0.0, 1.5}) {
    for (int which = 0; which < 2; ++which) {
      const double jn = which == 0 ? 0.0 : 2.0, mu = which == 0 ? 0.4 : 0.0;
      const Vec2 v0 = -0.7 * kN + vt * kT;
      Vec2 w = v0;
      const double jt0 = friction_impulse(kN, jn, mu, 1.5, w);
      INFO("jn = " << jn << ", mu = " << mu << ", |v_t| = " << vt);
      wbtest::require_finite(wb::Mat2X(w), "velocity with mu jn = 0");
      require_near(w, v0, kRound, "mu jn = 0: no friction, velocity unchanged");
      require_near(jt0, 0.0, kRound, "mu jn = 0: returned impulse 0");
    }
  }
}

TEST_CASE(
    "C4 friction_impulse: the cone compares the impulse m |v_t| with mu jn so the mass "
    "decides",
    "[collisions][C4][2pts]") {
  // The same tangential speed and bound, two masses: what decides is the impulse
  // needed to stop the sliding, m |v_t|, against mu jn (not |v_t| alone).
  struct Case {
    double m, vt, jn, mu;  // m |v_t| against mu jn
    bool sticks;
  };
  const Case cases[] = {
      {4.0, 0.2, 1.0, 0.5, false},    // 0.8 > 0.5: slides (|v_t| = 0.2 < 0.5 would stick)
      {0.25, 1.0, 1.0, 0.5, true},    // 0.25 <= 0.5: sticks (|v_t| = 1 > 0.5 would slide)
      {2.0, 0.505, 2.0, 0.5, false},  // 1.01 > 1.0: just outside the cone
      {2.0, 0.495, 2.0, 0.5, true},   // 0.99 <= 1.0: just inside
  };
  for (const Case& c : cases) {
    Vec2 v = -0.3 * kN + c.vt * kT;
    const double jt = friction_impulse(kN, c.jn, c.mu, c.m, v);
    const double bound = c.mu * c.jn;
    INFO("m = " << c.m << ", |v_t| = " << c.vt << ", mu jn = " << bound << ": m |v_t| = "
                << c.m * c.vt << (c.sticks ? " <= mu jn: static" : " > mu jn: sliding"));
    if (c.sticks) {
      require_near(v, Vec2(-0.3 * kN), kRound, "static: the tangential velocity is stopped");
      require_near(jt, c.m * c.vt, kRound, "static: returned impulse m |v_t|");
    } else {
      require_near(v, Vec2(-0.3 * kN + (c.vt - bound / c.m) * kT), kRound,
                   "sliding: the tangential speed drops by mu jn / m");
      require_near(jt, bound, kRound, "sliding: returned impulse mu jn");
    }
  }
}

TEST_CASE("C4 held-out: random contacts inside and outside the friction cone follow the header",
          "[collisions][C4][held-out][3pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("C4")) {
    INFO(g.replay());
    for (int s = 0; s < 18; ++s) {
      // The first two along an axis, so that v_t = 0 exactly (and mu jn = 0 in the first).
      const Vec2 n = s < 2 ? Vec2(0, g.sign()) : Vec2(g.unit2()), t(-n.y(), n.x());
      // The last two: a mass well above 1, then well below, and a sliding speed between
      // mu jn / m and mu jn: the cone compares the impulse m |v_t|, not the speed.
      const double m = s == 16   ? g.uniform(2.0, 5.0)
                       : s == 17 ? g.uniform(0.1, 0.5)
                                 : g.uniform(0.1, 5.0);
      const double mu = s == 0 ? 0.0 : s >= 16 ? g.uniform(0.3, 1.5) : g.uniform(0.0, 1.5);
      const double jn = s == 0 ? 0.0 : s >= 16 ? g.uniform(0.5, 5.0) : g.uniform(0.0, 5.0);
      // Tangential speed: none, inside the cone, or outside it.
      const double between = mu * jn *
                             (m > 1 ? 1.0 / m + g.uniform(0.2, 0.8) * (1.0 - 1.0 / m)
                                    : 1.0 + g.uniform(0.2, 0.8) * (1.0 / m - 1.0));
      const double vt = s < 2     ? 0.0
                        : s >= 16 ? g.sign() * between
                                  : g.sign() *
                                        (g.coin() ? g.uniform(0.0, 0.95) : g.uniform(1.05, 4.0)) *
                                        (mu * jn / m + (s % 3 == 0 ? g.uniform(0.0, 1.0) : 0.0));
      const Vec2 v0 = g.uniform(-3, 3) * n + vt * t;
      const Vec2 vtv = v0 - v0.dot(n) * n;
      Vec2 ve = v0;
      double je;
      if (m * vtv.norm() <= mu * jn) {
        ve = v0 - vtv;
        je = m * vtv.norm();
      } else {
        ve = v0 - (mu * jn / m) * vtv / vtv.norm();
        je = mu * jn;
      }
      Vec2 v = v0;
      const double j = friction_impulse(n, jn, mu, m, v);
      INFO("n = " << wbtest::str(n) << ", jn = " << jn << ", mu = " << mu << ", m = " << m
                  << ", v = " << wbtest::str(v0) << " (m |v_t| = " << m * vtv.norm()
                  << ", mu jn = " << mu * jn << ")");
      wbtest::require_near(v, ve, 1e-12 * (1 + v0.norm()),
                           "static (m |v_t| <= mu jn): v_t stopped; sliding: v_t reduced by "
                           "mu jn / m; the normal part untouched");
      wbtest::require_near(j, je, 1e-12 * (1 + je), "the tangential impulse: m |v_t| or mu jn");
    }
  }
}

}  // namespace test_C4_friction_impulse
