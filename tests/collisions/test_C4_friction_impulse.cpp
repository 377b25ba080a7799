// Graded tests for C4, Coulomb friction (labs/collisions/friction_impulse.cpp).
// Expected values: Coulomb's law (the tangential impulse stops the sliding if
// that takes at most mu jn, else it is mu jn against the sliding), and the
// block on a slope of angle theta: at rest for tan theta <= mu, otherwise
// sliding with acceleration g (sin theta - mu cos theta).
#include <cmath>

#include "collisions_params.h"
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
const Vec2 kN(0.6, 0.8);

// The public tests' scenarios, each a function of its parameters: the public test runs it with
// the published ones (wbtest::Params()), the held-out test with drawn ones in the same format
// (tests/common/params.h, collisions_params.h): short decimals within a quarter or so of the
// published value, the normal among short-decimal unit vectors.

// The block's mass on the slopes, held-out too: it is the largest number of most of the slopes'
// calls (the speeds pass it late in the slide), and a drawn one would set the held-out calls
// apart on that alone (a mass below 2 in half of them). The mass is tried by every other
// scenario.
constexpr double kSlopeMass = 2.0;

// Slides a block of mass m on a slope of angle theta (plane through 0 with normal n) for
// `steps` steps of semi-implicit Euler: gravity, the normal impulse that
// cancels the approach (resting, e = 0), then friction. Returns the velocity.
Vec2 slide(double theta, double mu, double m, long steps, double h, Vec2& x) {
  const double g = 9.81;
  const Vec2 n(-std::sin(theta), std::cos(theta));
  Vec2 v(0, 0);
  for (long k = 0; k < steps; ++k) {
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

// m |v_t| <= mu jn: the tangential velocity stops (drawn: m |v_t| <= 0.75 < 1 <= mu jn).
void inside_cone(const wbtest::Params& p) {
  const Vec2 n = collisionstest::short_unit(p, kN), t = wb::perp(n);
  const double vn = p.num(-0.5, -1.0, -0.2), vt = collisionstest::sign(p) * p.num(0.2, 0.1, 0.3);
  const double jn = p.num(3.0, 2.5, 3.5), mu = p.num(0.5, 0.4, 0.6), m = p.num(2.0, 1.5, 2.5);
  Vec2 v = vn * n + vt * t;
  const double jt = friction_impulse(n, jn, mu, m, v);
  INFO("n = " << wbtest::str(n) << ", v.n = " << vn << ", v.t = " << vt << ", jn = " << jn
              << ", mu = " << mu << ", m = " << m);
  require_near(v, Vec2(vn * n), kRound, "static friction: tangential velocity 0, normal kept");
  require_near(jt, m * std::abs(vt), kRound, "returned impulse m |v_t|");
}

// m |v_t| > mu jn: the tangential speed drops by mu jn / m (drawn: m |v_t| >= 3 > 0.75 >= mu jn).
void outside_cone(const wbtest::Params& p) {
  const Vec2 n = collisionstest::short_unit(p, kN), t = wb::perp(n);
  const double vn = p.num(0.1, -0.3, 0.3), vt = collisionstest::sign(p) * p.num(3.0, 2.0, 4.0);
  const double jn = p.num(1.0, 0.5, 1.5), mu = p.num(0.4, 0.3, 0.5), m = p.num(2.0, 1.5, 2.5);
  Vec2 v = vn * n + vt * t;
  const double jt = friction_impulse(n, jn, mu, m, v);
  INFO("n = " << wbtest::str(n) << ", v.n = " << vn << ", v.t = " << vt << ", jn = " << jn
              << ", mu = " << mu << ", m = " << m);
  require_near(v, Vec2(vn * n + (vt - std::copysign(mu * jn / m, vt)) * t), kRound,
               "sliding: tangential speed drops by mu jn / m, normal velocity kept");
  require_near(jt, mu * jn, kRound, "returned impulse mu jn");
}

// tan theta < mu: the block stays put. Held-out: theta, mu, h and the start drawn (tan
// theta <= 0.41 < 0.45 <= mu), 250 steps (the share of calls the public test's 2000 have).
void slope_sticks(const wbtest::Params& p) {
  const double theta = p.num(20.0, 16.0, 22.0) * M_PI / 180.0, mu = p.num(0.5, 0.45, 0.6);
  const double m = kSlopeMass, h = p.num(1e-3, 8e-4, 1.2e-3);
  const Vec2 x0(p.num(0.25, 0.1, 0.4), p.num(-0.5, -0.7, -0.3));
  Vec2 x = x0;
  const Vec2 v = slide(theta, mu, m, p.steps(2000, 250), h, x);
  INFO("theta = " << theta << " rad (tan theta = " << std::tan(theta) << "), mu = " << mu
                  << ", m = " << m << ", h = " << h);
  constexpr double kStickTol = 1e-12;  // rounding of the normal impulse each step
  require_near(v.norm(), 0.0, kStickTol, "speed of a block that static friction holds");
  require_near(x, x0, 1e-12, "position of a block that static friction holds");
}

// tan theta > mu: it slides with a = g (sin theta - mu cos theta). Held-out: theta and mu
// drawn, 250 steps (the share of calls the public test's 1000 have) of a step 3 to 5 times
// the published one, so that the block slides about as long and as fast.
void slope_slides(const wbtest::Params& p) {
  const double theta = p.num(35.0, 30.0, 40.0) * M_PI / 180.0, mu = p.num(0.3, 0.2, 0.4);
  const double m = kSlopeMass, g = 9.81, h = p.num(1e-3, 3e-3, 5e-3);
  const long steps = p.steps(1000, 250);
  Vec2 x(0, 0);
  const Vec2 v = slide(theta, mu, m, steps, h, x);
  const Vec2 down(-std::cos(theta), -std::sin(theta));  // down the slope
  // Each step: gravity adds g h (sin theta) along the slope and g h cos theta
  // into it; the normal impulse cancels the latter and friction removes mu times
  // it: the speed grows by exactly h g (sin - mu cos) per step (no step-size error).
  const double a = g * (std::sin(theta) - mu * std::cos(theta));
  INFO("theta = " << theta << " rad, mu = " << mu << ", m = " << m << ", h = " << h << ", "
                  << steps << " steps");
  require_near(v, Vec2(a * double(steps) * h * down), 1e-10,
               "velocity after the run: a t down the slope (rounding over the steps)");
}

// The impulse opposes the sliding both ways; no sliding, jn = 0 or mu = 0 give no NaN.
void both_ways_and_degenerate(const wbtest::Params& p) {
  const Vec2 n = collisionstest::short_unit(p, kN), t = wb::perp(n);
  const double jn = p.num(2.0, 1.5, 2.5), mu = p.num(0.25, 0.2, 0.3), m = p.num(1.0, 0.8, 1.2);
  const double vn = p.num(-0.2, -0.4, -0.1), speed = p.num(1.5, 1.2, 1.8);
  for (double s : {1.0, -1.0}) {
    Vec2 v = vn * n + s * speed * t;
    friction_impulse(n, jn, mu, m, v);  // bound mu jn / m <= 0.94 < 1.2: sliding
    INFO("tangential direction " << s << ", n = " << wbtest::str(n) << ", v.t = " << s * speed
                                 << ", mu jn / m = " << mu * jn / m);
    require_near(v, Vec2(vn * n + s * (speed - mu * jn / m) * t), kRound,
                 "speed |v_t| - mu jn / m");
  }
  const double vn2 = p.num(-0.7, -0.9, -0.5);
  Vec2 v = vn2 * n;  // no tangential velocity
  const double jt = friction_impulse(n, jn, mu, m, v);
  wbtest::require_finite(wb::Mat2X(v), "velocity with no tangential part");
  require_near(v, Vec2(vn2 * n), kRound, "nothing to stop: velocity unchanged");
  require_near(jt, 0.0, kRound, "no tangential impulse");
  // jn = 0 (no contact this step) or mu = 0 (ice): the cone is the point 0, so the
  // tangential impulse is 0, with or without sliding (v_t = 0 included: no 0 / 0).
  const double m2 = p.num(1.5, 1.2, 1.8);
  for (double vt : {0.0, speed}) {
    for (int which = 0; which < 2; ++which) {
      const double jn0 = which == 0 ? 0.0 : jn, mu0 = which == 0 ? p.num(0.4, 0.3, 0.5) : 0.0;
      const Vec2 v0 = vn2 * n + vt * t;
      Vec2 w = v0;
      const double jt0 = friction_impulse(n, jn0, mu0, m2, w);
      INFO("jn = " << jn0 << ", mu = " << mu0 << ", |v_t| = " << vt);
      wbtest::require_finite(wb::Mat2X(w), "velocity with mu jn = 0");
      require_near(w, v0, kRound, "mu jn = 0: no friction, velocity unchanged");
      require_near(jt0, 0.0, kRound, "mu jn = 0: returned impulse 0");
    }
  }
}

// The same tangential speed and bound, two masses: what decides is the impulse needed to stop
// the sliding, m |v_t|, against mu jn (not |v_t| alone). Held-out: every value drawn within a
// few per cent of the published one (each case stays on its side of the cone).
void mass_decides(const wbtest::Params& p) {
  struct Case {
    double m, vt, jn, mu;  // m |v_t| against mu jn
  };
  const Case cases[] = {
      {4.0, 0.2, 1.0, 0.5},    // 0.8 > 0.5: slides (|v_t| = 0.2 < 0.5 would stick)
      {0.25, 1.0, 1.0, 0.5},   // 0.25 <= 0.5: sticks (|v_t| = 1 > 0.5 would slide)
      {2.0, 0.505, 2.0, 0.5},  // 1.01 > 1.0: just outside the cone
      {2.0, 0.495, 2.0, 0.5},  // 0.99 <= 1.0: just inside
  };
  const Vec2 n = collisionstest::short_unit(p, kN), t = wb::perp(n);
  const double vn = p.num(-0.3, -0.5, -0.1);
  for (const Case& k : cases) {
    // Held-out: mu jn and m drawn, |v_t| so that m |v_t| / (mu jn) is the published ratio.
    const double m = p.num(k.m, 0.9 * k.m, 1.1 * k.m), jn = p.num(k.jn, 0.9 * k.jn, 1.1 * k.jn),
                 mu = p.num(k.mu, 0.9 * k.mu, 1.1 * k.mu);
    const double vt =
        p.held_out() ? wbtest::Params::short_decimal(k.m * k.vt / (k.mu * k.jn) * mu * jn / m)
                     : k.vt;
    const double bound = mu * jn;
    const bool sticks = m * vt <= bound;
    Vec2 v = vn * n + vt * t;
    const double jt = friction_impulse(n, jn, mu, m, v);
    INFO("m = " << m << ", |v_t| = " << vt << ", mu jn = " << bound << ": m |v_t| = " << m * vt
                << (sticks ? " <= mu jn: static" : " > mu jn: sliding"));
    if (sticks) {
      require_near(v, Vec2(vn * n), kRound, "static: the tangential velocity is stopped");
      require_near(jt, m * vt, kRound, "static: returned impulse m |v_t|");
    } else {
      require_near(v, Vec2(vn * n + (vt - bound / m) * t), kRound,
                   "sliding: the tangential speed drops by mu jn / m");
      require_near(jt, bound, kRound, "sliding: returned impulse mu jn");
    }
  }
}

// The held-out test's own draws: every situation the header names (no sliding with mu jn = 0,
// inside and outside the cone, a mass well above and well below 1 with a sliding speed between
// mu jn / m and mu jn), its numbers short decimals and its normal a short-decimal unit vector,
// as the public tests write theirs.
void random_contacts(wbtest::HeldOut& g) {
  const wbtest::Params p(g);
  auto dec = [](double x) { return wbtest::Params::short_decimal(x); };
  for (int s = 0; s < 18; ++s) {
    // The first two along an axis, so that v_t = 0 exactly (and mu jn = 0 in the first).
    const Vec2 n = collisionstest::short_unit(p, kN, s < 2), t = wb::perp(n);
    // The last two: a mass well above 1, then well below, and a sliding speed between
    // mu jn / m and mu jn: the cone compares the impulse m |v_t|, not the speed.
    const double m = s == 16   ? p.num(2, 2.0, 5.0)
                     : s == 17 ? p.num(0.1, 0.1, 0.5)
                               : p.num(1, 0.1, 5.0);
    const double mu = s == 0 ? 0.0 : s >= 16 ? p.num(1, 0.3, 1.5) : p.num(1, 0.0, 1.5);
    const double jn = s == 0 ? 0.0 : s >= 16 ? p.num(1, 0.5, 5.0) : p.num(1, 0.0, 5.0);
    // Tangential speed: none, inside the cone, or outside it.
    const double between = mu * jn *
                           (m > 1 ? 1.0 / m + g.uniform(0.2, 0.8) * (1.0 - 1.0 / m)
                                  : 1.0 + g.uniform(0.2, 0.8) * (1.0 / m - 1.0));
    const double vt =
        s < 2     ? 0.0
        : s >= 16 ? g.sign() * dec(between)
                  : g.sign() * dec((g.coin() ? g.uniform(0.0, 0.95) : g.uniform(1.05, 4.0)) *
                                   (mu * jn / m + (s % 3 == 0 ? g.uniform(0.0, 1.0) : 0.0)));
    const Vec2 v0 = p.num(0, -3, 3) * n + vt * t;
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

}  // namespace

TEST_CASE("C4 friction_impulse: inside the friction cone the tangential velocity stops",
          "[collisions][C4][2pts]") {
  inside_cone(wbtest::Params());
}

TEST_CASE("C4 friction_impulse: outside the cone the impulse is mu jn against the sliding",
          "[collisions][C4][2pts]") {
  outside_cone(wbtest::Params());
}

TEST_CASE("C4 friction_impulse: a block on a slope sticks when tan theta < mu",
          "[collisions][C4][2pts]") {
  slope_sticks(wbtest::Params());
}

TEST_CASE(
    "C4 friction_impulse: on a steeper slope it slides with a = g (sin theta - mu cos "
    "theta)",
    "[collisions][C4][2pts]") {
  slope_slides(wbtest::Params());
}

TEST_CASE(
    "C4 friction_impulse: the impulse opposes the sliding in both directions and no sliding "
    "or mu jn = 0 gives no NaN",
    "[collisions][C4][2pts]") {
  both_ways_and_degenerate(wbtest::Params());
}

TEST_CASE(
    "C4 friction_impulse: the cone compares the impulse m |v_t| with mu jn so the mass "
    "decides",
    "[collisions][C4][2pts]") {
  mass_decides(wbtest::Params());
}

// Every public scenario above again, its parameters drawn from the held-out seed in the public
// tests' format, each scenario's calls in the share they have among the public tests' calls,
// then the held-out test's own random contacts in the same format (tools/adversary --inputs).
TEST_CASE("C4 held-out: random contacts inside and outside the friction cone follow the header",
          "[collisions][C4][held-out][3pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("C4")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    inside_cone(p);
    outside_cone(p);
    slope_sticks(p);
    slope_slides(p);
    both_ways_and_degenerate(p);
    mass_decides(p);
    random_contacts(g);
  }
}

}  // namespace test_C4_friction_impulse
