// F5 spring-damper: f_i = -(k (L - rest) + kd (v_i - v_j) . u) u, u = (x_i - x_j) / L
// (labs/forces/spring.h).
#include <cmath>

#include "heldout.h"
#include "spring.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F5_spring {

using wb::Mat2X;
using wb::Vec2;

namespace {
// Hand-derived values below are short decimals: rounding only.
constexpr double kTol = 1e-12;
}  // namespace

TEST_CASE("F5 spring: a stretched spring pulls i towards j with k (L - rest)",
          "[forces][F5][3pts]") {
  // x_i = (1, 2), x_j = (4, 6): d = x_i - x_j = (-3, -4), L = 5, u = (-0.6, -0.8).
  // k = 10, rest = 2: tension k (L - rest) = 30, f_i = -30 u = (18, 24), along
  // x_j - x_i. Both ends move with the same velocity, so the damper adds nothing.
  const Vec2 xi(1, 2), xj(4, 6), v(0.3, -0.7);
  const Vec2 fi = spring_force(xi, xj, v, v, 10.0, 2.0, 0.5);
  wbtest::require_near(fi, Vec2(18, 24), kTol,
                       "Hooke's law: a spring stretched by L - rest = 3 pulls end i towards j "
                       "with k (L - rest) = 30",
                       kTol);
  // The same spring seen from end j.
  const Vec2 fj = spring_force(xj, xi, v, v, 10.0, 2.0, 0.5);
  wbtest::require_near(fj, Vec2(-18, -24), kTol,
                       "seen from the other end the spring pulls j towards i (f_j = -f_i)", kTol);
}

TEST_CASE("F5 spring: a compressed spring pushes apart and a spring at rest length does nothing",
          "[forces][F5][2pts]") {
  // Same ends as above (L = 5, u = (-0.6, -0.8)), k = 10.
  // rest = 7: tension 10 (5 - 7) = -20, f_i = 20 u = (-12, -16), away from j.
  const Vec2 xi(1, 2), xj(4, 6), zero(0, 0);
  wbtest::require_near(spring_force(xi, xj, zero, zero, 10.0, 7.0, 0.0), Vec2(-12, -16), kTol,
                       "Hooke's law: a spring compressed by 2 pushes end i away from j with "
                       "k (rest - L) = 20",
                       kTol);
  // rest = 5 = L: no force.
  wbtest::require_near(spring_force(xi, xj, zero, zero, 10.0, 5.0, 0.0), Vec2(0, 0), kTol,
                       "a spring at its rest length exerts no force");
}

TEST_CASE("F5 spring: the spring force is minus the gradient of 1/2 k (L - rest)^2",
          "[forces][F5][2pts]") {
  // Random ends 0.5 to 3 apart, random rest lengths, no damping. Central
  // differences, h = 1e-5: truncation h^2/6 |V'''| with |V'''| ~ 3 k / L < 100
  // here gives < 2e-9, rounding eps_mach |V| / h ~ 1e-16 * 50 / 1e-5 = 5e-10;
  // tolerance 1e-7.
  const Mat2X a = wbtest::random_points(6, 5, -1.5, 1.5);
  const Mat2X b = wbtest::random_points(6, 6, -1.5, 1.5);
  const Mat2X r = wbtest::random_points(6, 8, 0.2, 2.0);
  const double k = 13.0, h = 1e-5, tol = 1e-7;
  int checked = 0;
  for (Eigen::Index s = 0; s < 6; ++s) {
    const Vec2 xi = a.col(s), xj = b.col(s);
    if ((xi - xj).norm() < 0.5) continue;  // keep V''' small
    const double rest = r(0, s);
    CAPTURE(s, rest);
    auto V = [&](const Mat2X& y) {
      const double stretch = (Vec2(y.col(0)) - xj).norm() - rest;
      return 0.5 * k * stretch * stretch;
    };
    const Mat2X expected = wbtest::minus_gradient(V, Mat2X(xi), h);
    const Vec2 zero(0, 0);
    wbtest::require_near(spring_force(xi, xj, zero, zero, k, rest, 0.0), Vec2(expected.col(0)),
                         tol, "the spring is conservative: f_i = -dV/dx_i", tol);
    ++checked;
  }
  INFO("the test itself checked " << checked
                                  << " of its 6 springs, expected at least 3 (a broken fixture, "
                                     "not your code)");
  REQUIRE(checked >= 3);  // nanfree: integers
}

TEST_CASE("F5 spring: the damper acts only along the spring", "[forces][F5][3pts]") {
  // x_i = (2, 1), x_j = (-1, -3): d = (3, 4), L = 5, u = (0.6, 0.8), perp = (-0.8, 0.6).
  // k = 7, kd = 2, v_j = (0.1, 0.2).
  const Vec2 xi(2, 1), xj(-1, -3), vj(0.1, 0.2), u(0.6, 0.8), perp(-0.8, 0.6);
  const double k = 7, kd = 2;

  // Ends separating at 1.5 m/s along u, spring at rest length (rest = 5):
  // f_i = -kd 1.5 u = -3 u = (-1.8, -2.4), resisting the separation.
  wbtest::require_near(spring_force(xi, xj, vj + 1.5 * u, vj, k, 5.0, kd), Vec2(-1.8, -2.4), kTol,
                       "the damper resists the rate of stretch: f_i = -kd ((v_i - v_j) . u) u",
                       kTol);

  // Relative velocity across the spring only: the length does not change,
  // so there is no damping force at all.
  wbtest::require_near(spring_force(xi, xj, vj + 2.0 * perp, vj, k, 5.0, kd), Vec2(0, 0), kTol,
                       "a relative velocity perpendicular to the spring does not change its "
                       "length: no damping force",
                       kTol);

  // Both at once: only the component along u counts, same force as the first case.
  wbtest::require_near(spring_force(xi, xj, vj + 1.5 * u + 2.0 * perp, vj, k, 5.0, kd),
                       Vec2(-1.8, -2.4), kTol,
                       "only the component of v_i - v_j along the spring is damped", kTol);

  // Spring and damper together, rest = 4: tension 7 * 1 + 2 * 1.5 = 10, f_i = -10 u.
  wbtest::require_near(
      spring_force(xi, xj, vj + 1.5 * u + 2.0 * perp, vj, k, 4.0, kd), Vec2(-6, -8), kTol,
      "spring and damper add along u: -(k (L - rest) + kd (v_i - v_j) . u) u", kTol);
}

TEST_CASE("F5 spring: anchored form and equal and opposite forces between particles",
          "[forces][F5][1pts]") {
  // Anchor (2, 1), x_i = (0.5, -1), v_i = (1, 2): d = (-1.5, -2), L = 2.5,
  // u = (-0.6, -0.8), (v_i - 0) . u = -2.2. k = 4, rest = 1, kd = 0.3:
  // tension 4 * 1.5 + 0.3 * (-2.2) = 5.34, f_i = -5.34 u = (3.204, 4.272).
  const Vec2 anchor(2, 1), xi(0.5, -1), vi(1, 2);
  wbtest::require_near(spring_force(xi, anchor, vi, Vec2(0, 0), 4.0, 1.0, 0.3),
                       Vec2(3.204, 4.272), kTol,
                       "spring to a fixed anchor (x_j = anchor, v_j = 0)", kTol);

  // Between two particles the forces on the two ends cancel (third law), so a
  // free spring does not change the total momentum.
  const Mat2X x = wbtest::random_points(8, 21, -2.0, 2.0);
  const Mat2X v = wbtest::random_points(8, 22, -1.0, 1.0);
  for (Eigen::Index s = 0; s + 1 < 8; s += 2) {
    CAPTURE(s);
    const Vec2 fi = spring_force(x.col(s), x.col(s + 1), v.col(s), v.col(s + 1), 5.0, 0.7, 0.4);
    const Vec2 fj = spring_force(x.col(s + 1), x.col(s), v.col(s + 1), v.col(s), 5.0, 0.7, 0.4);
    wbtest::require_near(Vec2(fi + fj), Vec2(0, 0), 1e-12 * (1 + fi.norm()),
                         "Newton's third law: f_j = -f_i for a spring between two particles");
  }
}

TEST_CASE("F5 spring: a zero-length spring returns zero and no NaN", "[forces][F5][2pts]") {
  // Both ends at (1.5, -0.5), rest = 0.8: the direction u is undefined and
  // the header says return (0, 0).
  const Vec2 x0(1.5, -0.5), vi(1, 0), vj(0, 1);
  const Vec2 f0 = spring_force(x0, x0, vi, vj, 10.0, 0.8, 1.0);
  {
    INFO("zero-length spring gave " << wbtest::str(f0));
    REQUIRE(f0.allFinite());
  }
  wbtest::require_near(f0, Vec2(0, 0), 0.0, "L == 0: no direction, so no force (header)");

  // The same spring with x_j = x_i + (0.3, 0.4): d = (-0.3, -0.4), L = 0.5,
  // u = (-0.6, -0.8), (v_i - v_j) . u = (1, -1) . u = 0.2:
  // tension 10 (0.5 - 0.8) + 1 * 0.2 = -2.8, f_i = 2.8 u = (-1.68, -2.24).
  wbtest::require_near(spring_force(x0, x0 + Vec2(0.3, 0.4), vi, vj, 10.0, 0.8, 1.0),
                       Vec2(-1.68, -2.24), kTol,
                       "a short compressed damped spring pushes i away from j", kTol);
}

TEST_CASE("F5 held-out: random springs give f_i = -(k (L - rest) + kd (v_i - v_j) . u) u",
          "[forces][F5][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F5")) {
    INFO(g.replay());
    for (int s = 0; s < 12; ++s) {
      const Vec2 xi = g.vec2(-3.0, 3.0), vi = g.vec2(-4.0, 4.0), vj = g.vec2(-4.0, 4.0);
      const Vec2 xj = s == 0 ? xi : Vec2(g.vec2(-3.0, 3.0));  // the first: zero length
      const double k = g.uniform(0.5, 50.0), rest = g.uniform(0.1, 4.0), kd = g.uniform(0.0, 3.0);
      const Vec2 d = xi - xj;
      const double L = d.norm();
      Vec2 expected(0, 0);
      if (L > 0) {
        const Vec2 u = d / L;
        expected = -(k * (L - rest) + kd * (vi - vj).dot(u)) * u;
      }
      INFO("x_i = " << wbtest::str(xi) << ", x_j = " << wbtest::str(xj)
                    << ", v_i = " << wbtest::str(vi) << ", v_j = " << wbtest::str(vj)
                    << ", k = " << k << ", rest = " << rest << ", kd = " << kd);
      wbtest::require_near(spring_force(xi, xj, vi, vj, k, rest, kd), expected,
                           1e-12 * (1.0 + expected.norm()),
                           "spring-damper f_i = -(k (L - rest) + kd (v_i - v_j) . u) u, "
                           "u = (x_i - x_j) / L, zero when L = 0",
                           1e-12);
    }
  }
}

}  // namespace test_F5_spring
