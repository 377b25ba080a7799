// F8 vortex field: a Rankine vortex u(x) and the drag f_i += c (u(x_i) - v_i)
// (labs/forces/vortex.h).
#include <cmath>
#include <string>

#include "heldout.h"
#include "params.h"
#include "test_helpers.h"
#include "vortex.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F8_vortex {

using wb::Mat2X;
using wb::Vec2;

namespace {

// Hand-derived values below are short decimals: rounding only. A drawn vortex's expected
// values are the formulas below, evaluated here in another order: a few ulps of |u|, so the
// same 1e-12 relative to the speed.
constexpr double kTol = 1e-12;

// The scenarios of the public tests below, each a function of its parameters: the public test
// runs it with the published ones (wbtest::Params()), the held-out test with drawn ones, in the
// same format (tests/common/params.h): short decimals where the public test writes them, the
// same sizes, about the same magnitudes, and each point in the regime (inside the core,
// outside it, on the axis) that the public test puts it in.

// The vortex of most tests: centre off the origin, core radius R = 2 (not 1,
// so R^2 / r and R^2 / r^2 differ at the core's edge), omega = 2.
// Held-out: every number drawn about the published one, R 1.7 to 2.3 (never 1) and c 1.2 to
// 1.8 (never 1).
VortexParams vortex(const wbtest::Params& q) {
  VortexParams p;
  p.center = Vec2(q.num(1.0, 0.5, 1.5), q.num(-1.0, -1.5, -0.5));
  p.omega = q.num(2.0, 1.7, 2.3);
  p.core = q.num(2.0, 1.7, 2.3);
  p.drag = q.num(1.5, 1.2, 1.8);
  return p;
}

// The Rankine flow, written out: omega perp(d) inside the core (r <= R), omega R^2 perp(d) /
// r^2 outside, d = x - center.
Vec2 rankine(const Vec2& x, const VortexParams& p) {
  const Vec2 d = x - p.center, perp(-d.y(), d.x());
  const double r = d.norm();
  return r <= p.core ? Vec2(p.omega * perp) : Vec2(p.omega * p.core * p.core * perp / (r * r));
}

// In the public test `published`; else a point at a distance drawn in [lo, hi] from the
// vortex's centre, in a drawn direction, written as the public test writes that point: each
// coordinate with the published one's significant digits (4 and 3 stay one-digit numbers, 1.6
// and -0.2 two and one). Rounding to one digit moves a coordinate by up to 0.5, so the rounded
// point is drawn again until it has those digits and still lies in [lo, hi] (its regime: inside
// the core, near its edge, outside it); 3 digits after 64 tries (a move under 0.01).
Vec2 at(const wbtest::Params& q, const Vec2& published, const VortexParams& p, double r,
        double lo, double hi) {
  if (!q.held_out()) return published;
  using wbtest::Params;
  const int dx = Params::digits(published.x()), dy = Params::digits(published.y());
  for (int tries = 0; tries < 64; ++tries) {
    const double d = q.num(r, lo, hi), angle = q.num(0.93, 0.0, 6.28);
    const Vec2 x(Params::rounded(p.center.x() + d * std::cos(angle), dx),
                 Params::rounded(p.center.y() + d * std::sin(angle), dy));
    const double dist = (x - p.center).norm();
    if (Params::digits(x.x()) == dx && Params::digits(x.y()) == dy && dist >= lo && dist <= hi)
      return x;
  }
  const double d = q.num(r, lo, hi), angle = q.num(0.93, 0.0, 6.28);
  return Vec2(Params::short_decimal(p.center.x() + d * std::cos(angle)),
              Params::short_decimal(p.center.y() + d * std::sin(angle)));
}
// Points inside the core (0.1 R to 0.9 R from the centre) and outside it (1.2 R to 2.6 R).
Vec2 inside(const wbtest::Params& q, const Vec2& published, const VortexParams& p, double r) {
  return at(q, published, p, r, 0.1 * p.core, 0.9 * p.core);
}
// A point inside the core near its edge (0.8 R to 0.93 R): beyond sqrt(R) for every drawn R
// of vortex() (0.8 R - sqrt(R) >= 0.056 at R = 1.7), so a core test of r^2 against R instead of
// R^2 reads it as outside on every seed.
Vec2 inside_near_edge(const wbtest::Params& q, const Vec2& published, const VortexParams& p,
                      double r) {
  return at(q, published, p, r, 0.8 * p.core, 0.93 * p.core);
}
Vec2 outside(const wbtest::Params& q, const Vec2& published, const VortexParams& p, double r) {
  return at(q, published, p, r, 1.2 * p.core, 2.6 * p.core);
}

// `published` (hand-derived) in the public test, the formula on a drawn vortex.
Vec2 expect(const wbtest::Params& q, const Vec2& published, const Vec2& x,
            const VortexParams& p) {
  return q.held_out() ? rankine(x, p) : published;
}

void solid_core(const wbtest::Params& q) {
  const VortexParams p = vortex(q);
  // x = (1.6, -0.2): d = (0.6, 0.8), r = 1 < R, perp(d) = (-0.8, 0.6),
  // u = omega perp(d) = (-1.6, 1.2), speed omega r = 2.
  const Vec2 a = inside(q, Vec2(1.6, -0.2), p, 1.0);
  wbtest::require_near(vortex_flow(a, p), expect(q, Vec2(-1.6, 1.2), a, p), kTol,
                       "solid rotation in the core: u = omega perp(x - center), speed omega r",
                       kTol);
  // x = (0.1, -2.2): d = (-0.9, -1.2), r = 1.5 < R, perp(d) = (1.2, -0.9),
  // u = (2.4, -1.8), speed omega r = 3.
  const Vec2 b = inside_near_edge(q, Vec2(0.1, -2.2), p, 1.5);
  wbtest::require_near(vortex_flow(b, p), expect(q, Vec2(2.4, -1.8), b, p), kTol,
                       "solid rotation in the core: u = omega perp(x - center), speed omega r",
                       kTol);
}

void outer_flow(const wbtest::Params& q) {
  const VortexParams p = vortex(q);
  // x = (4, 3): d = (3, 4), r = 5 > R, perp(d) = (-4, 3),
  // u = omega R^2 perp(d) / r^2 = 8 (-4, 3) / 25 = (-1.28, 0.96), speed 8 / 5 = omega R^2 / r.
  const Vec2 a = outside(q, Vec2(4, 3), p, 5.0);
  wbtest::require_near(vortex_flow(a, p), expect(q, Vec2(-1.28, 0.96), a, p), kTol,
                       "irrotational outside: u = omega R^2 perp(d) / r^2, speed omega R^2 / r",
                       kTol);
  // x = (-1.4, 0.8): d = (-2.4, 1.8), r = 3, perp(d) = (-1.8, -2.4),
  // u = 8 (-1.8, -2.4) / 9 = (-1.6, -32/15), speed 8 / 3.
  const Vec2 b = outside(q, Vec2(-1.4, 0.8), p, 3.0);
  wbtest::require_near(vortex_flow(b, p), expect(q, Vec2(-1.6, -32.0 / 15), b, p), kTol,
                       "irrotational outside: u = omega R^2 perp(d) / r^2, speed omega R^2 / r",
                       kTol);
}

void continuity(const wbtest::Params& q) {
  const VortexParams p = vortex(q);
  // Along the unit direction (0.6, -0.8), just inside and just outside r = R = 2.
  // Both formulas give omega R perp(unit) = 4 (0.8, 0.6) = (3.2, 2.4) at r = R; a
  // step of 2e-9 in r changes u by at most omega * 2e-9 ~ 4e-9: tolerance 1e-7.
  // Held-out: the direction drawn (omega R 2e-9 stays below 2e-8).
  const double angle = q.num(5.36, 0.0, 6.28);
  const Vec2 unit = q.held_out() ? Vec2(std::cos(angle), std::sin(angle)) : Vec2(0.6, -0.8);
  const Vec2 on_core =
      q.held_out() ? Vec2(p.omega * p.core * Vec2(-unit.y(), unit.x())) : Vec2(3.2, 2.4);
  const double tol = 1e-7;
  const Vec2 u_in = vortex_flow(p.center + (p.core * (1 - 1e-9)) * unit, p);
  const Vec2 u_out = vortex_flow(p.center + (p.core * (1 + 1e-9)) * unit, p);
  wbtest::require_near(u_in, on_core, tol, "just inside the core: u = omega R perp(unit)");
  wbtest::require_near(
      u_out, on_core, tol,
      "just outside the core: u = omega R^2 perp(d) / r^2 -> omega R perp(unit), "
      "the same as inside (a Rankine vortex has no jump)");

  // The axis itself does not move.
  const Vec2 u0 = vortex_flow(p.center, p);
  {
    INFO("flow at the centre gave " << wbtest::str(u0));
    REQUIRE(u0.allFinite());
  }
  wbtest::require_near(u0, Vec2(0, 0), 0.0, "the vortex axis is at rest: u(center) = 0");
}

void drag(const wbtest::Params& q) {
  const VortexParams p = vortex(q);  // c = 1.5
  // The first and the last particle feel a non-zero drag, so that a loop
  // that skips either end leaves a column wrong.
  // Particle 0 at (4, 3) at rest: f = 1.5 (-1.28, 0.96) = (-1.92, 1.44).
  // Particle 1 at (1.6, -0.2) moves with the flow, v = u = (-1.6, 1.2): no force.
  // Particle 2 on the axis at rest: u = 0, v = 0, no force.
  // Particle 3 at (0.1, -2.2), v = (1, 1): f = 1.5 ((2.4, -1.8) - (1, 1)) = (2.1, -4.2).
  // Held-out: the same four situations drawn (particle 1's velocity the flow's, written with
  // two digits as the published one: it then feels a small drag, checked by the formula).
  Mat2X x(2, 4), v(2, 4), f(2, 4);
  x.col(0) = outside(q, Vec2(4.0, 3.0), p, 5.0);
  x.col(1) = inside(q, Vec2(1.6, -0.2), p, 1.0);
  x.col(2) = p.center;
  x.col(3) = inside(q, Vec2(0.1, -2.2), p, 1.5);
  const Vec2 u1 = rankine(x.col(1), p);
  v.col(0) = Vec2(0, 0);
  v.col(1) = q.held_out()
                 ? Vec2(wbtest::Params::rounded(u1.x(), 2), wbtest::Params::rounded(u1.y(), 2))
                 : Vec2(-1.6, 1.2);
  v.col(2) = Vec2(0, 0);
  v.col(3) = Vec2(q.num(1.0, -1.5, 1.5), q.num(1.0, -1.5, 1.5));
  const Mat2X f0 = (Mat2X(2, 4) << 2.0, 1.0, 4.0, 3.0,  // forces already there: add to them
                    0.0, -1.0, 0.25, 0.5)
                       .finished();
  for (Eigen::Index i = 0; i < 4; ++i)
    f.col(i) = Vec2(q.num(f0(0, i), -5.0, 5.0), q.num(f0(1, i), -5.0, 5.0));
  Mat2X expected = f;
  add_vortex(x, v, p, f);
  wbtest::require_finite(f, "vortex drag with a particle on the axis");
  if (q.held_out()) {
    for (Eigen::Index i = 0; i < 4; ++i)
      expected.col(i) += p.drag * (rankine(x.col(i), p) - v.col(i));
  } else {
    expected << 2.0 - 1.92, 1.0, 4.0, 3.0 + 2.1,  //
        1.44, -1.0, 0.25, 0.5 - 4.2;
  }
  wbtest::require_near(f, expected, kTol,
                       "drag towards the flow: f_i += c (u(x_i) - v_i) for EVERY particle i "
                       "(first and last included), added to f",
                       kTol);
}

void turning_sense(const wbtest::Params& q) {
  VortexParams p = vortex(q);
  // Eight points, each under both senses in turn. Held-out: the same points (this test's 16
  // calls are most of the task's public ones: fresh ones would make their magnitudes a
  // property of the held-out calls), the vortex and both senses' rates drawn about them.
  const Mat2X pts = wbtest::random_points(8, 41, -4.0, 4.0);
  const double omegas[2] = {q.num(2.0, 1.7, 2.3), q.num(-1.5, -1.8, -1.2)};
  for (Eigen::Index i = 0; i < pts.cols(); ++i) {
    for (double omega : omegas) {
      p.omega = omega;
      const Vec2 d = Vec2(pts.col(i)) - p.center;
      if (d.norm() < 1e-3) continue;
      const double turn = wb::cross(d, vortex_flow(pts.col(i), p));  // > 0: counter-clockwise
      CAPTURE(omega, i, turn);
      INFO(
          "the flow must turn in the sense of omega: cross(x - center, u) has the sign of omega");
      REQUIRE(wbtest::finite(turn) * omega > 0);
    }
  }
  // omega = -1.5 at (4, 3): -1.5 * 4 (-4, 3) / 25 = (0.96, -0.72).
  const Vec2 a = outside(q, Vec2(4, 3), p, 5.0);
  wbtest::require_near(vortex_flow(a, p), expect(q, Vec2(0.96, -0.72), a, p), kTol,
                       "omega < 0: the same flow reversed", kTol);
}

// The held-out test's own vortices: both senses of turning in every draw (omega's sign says
// which way the flow turns), 3 to 5 particles (as the public drag's 4) alternately inside and
// outside the core, one on the axis, numbers as the public tests write them.
void random_vortices(wbtest::HeldOut& g) {
  const wbtest::Params q(g);
  for (const double sense : {1.0, -1.0}) {
    VortexParams p;
    p.center = Vec2(q.num(0, 0.0, 2.0), q.num(0, -2.0, 0.0));
    p.omega = sense * q.num(0, 0.5, 2.5);
    p.core = q.num(0, 1.0, 2.5);
    p.drag = q.num(0, 0.5, 2.0);
    const Eigen::Index n = q.count(4, 3, 5);
    Mat2X x(2, n), v(2, n), f0(2, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      x.col(i) = i % 2 ? inside(q, Vec2(0, 0), p, 0) : outside(q, Vec2(0, 0), p, 0);
      v.col(i) = Vec2(q.num(0, -2.0, 2.0), q.num(0, -2.0, 2.0));
      f0.col(i) = Vec2(q.num(0, -4.0, 4.0), q.num(0, -4.0, 4.0));
    }
    x.col(g.integer(0, n - 1)) = p.center;
    Mat2X expected = f0;
    for (Eigen::Index i = 0; i < n; ++i)
      expected.col(i) += p.drag * (rankine(x.col(i), p) - v.col(i));
    Mat2X f = f0;
    add_vortex(x, v, p, f);
    INFO("x = " << x << "\n  v = " << v << "\n  center " << wbtest::str(p.center)
                << ", omega = " << p.omega << ", core R = " << p.core << ", drag c = " << p.drag);
    wbtest::require_near(f, expected, 1e-11,
                         "f_i += c (u(x_i) - v_i) for every particle, u = omega perp(d) inside "
                         "the core, omega R^2 perp(d) / r^2 outside",
                         1e-12);
  }
}

}  // namespace

TEST_CASE("F8 vortex: inside the core the flow turns like a solid disc", "[forces][F8][2pts]") {
  solid_core(wbtest::Params());
}

TEST_CASE("F8 vortex: outside the core the speed falls off as omega R^2 / r",
          "[forces][F8][2pts]") {
  outer_flow(wbtest::Params());
}

TEST_CASE("F8 vortex: the flow is continuous at the core radius and zero at the centre",
          "[forces][F8][1pts]") {
  continuity(wbtest::Params());
}

TEST_CASE("F8 vortex: drag c (u - v) towards the flow is zero for a particle moving with it",
          "[forces][F8][3pts]") {
  drag(wbtest::Params());
}

TEST_CASE("F8 vortex: omega > 0 turns counter-clockwise and omega < 0 clockwise",
          "[forces][F8][1pts]") {
  turning_sense(wbtest::Params());
}

// Every public scenario above again, its parameters drawn from the held-out seed in the public
// tests' format (short decimals, the same sizes, about the same magnitudes, each scenario's
// calls in the share they have among the public tests' calls), so that no call tells the public
// tests from this one (tools/adversary --inputs); then vortices of the test's own.
TEST_CASE("F8 held-out: random vortices and particles inside and outside the core",
          "[forces][F8][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F8")) {
    INFO(g.replay());
    const wbtest::Params q(g);
    solid_core(q);
    outer_flow(q);
    continuity(q);
    drag(q);
    turning_sense(q);
    random_vortices(g);
  }
}

}  // namespace test_F8_vortex
