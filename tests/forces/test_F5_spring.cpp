// F5 spring-damper: f_i = -(k (L - rest) + kd (v_i - v_j) . u) u, u = (x_i - x_j) / L
// (labs/forces/spring.h).
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "heldout.h"
#include "params.h"
#include "spring.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F5_spring {

using wb::Mat2X;
using wb::Vec2;

namespace {
// Hand-derived values (published) or the law computed here from short decimals: rounding
// only.
constexpr double kTol = 1e-12;

// The header's law, written out: -(k (L - rest) + kd (v_i - v_j) . u) u, zero when L = 0.
Vec2 spring_law(const Vec2& xi, const Vec2& xj, const Vec2& vi, const Vec2& vj, double k,
                double rest, double kd) {
  const Vec2 d = xi - xj;
  const double L = d.norm();
  if (L == 0.0) return Vec2(0, 0);
  const Vec2 u = d / L;
  return -(k * (L - rest) + kd * (vi - vj).dot(u)) * u;
}

// The scenarios of the public tests below, each a function of its parameters: the public test
// runs it with the published ones (wbtest::Params()), the held-out test with drawn ones, in the
// same format (tests/common/params.h): short decimals where the published values are, derived
// values derived as published, points from a drawn seed where the public test draws its own,
// about the published magnitudes.

// x as a decimal of 6 significant digits: a sum or multiple of short decimals, exact as a
// decimal, becomes the nearest double to that decimal (as a public test writes it), so that
// lengths built from it hold to rounding (Params::short_decimal keeps only 3 digits).
double decimal(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return std::strtod(buf, nullptr);
}

// Two ends d = c (3, 4) apart (L = 5 c, u = (0.6, 0.8) along d): x_j = x_i + sign c (3, 4),
// written as decimals; published c = 1. Held-out: x_i and c drawn (c from 0.7 to 1.3).
struct Ends {
  Vec2 xi, xj;
  double c;
  Ends(const wbtest::Params& p, const Vec2& published_xi, double sign)
      : xi(p.num(published_xi.x(), published_xi.x() - 0.5, published_xi.x() + 0.5),
           p.num(published_xi.y(), published_xi.y() - 0.5, published_xi.y() + 0.5)),
        c(p.num(1.0, 0.7, 1.3)) {
    xj = Vec2(decimal(xi.x() + sign * 3.0 * c), decimal(xi.y() + sign * 4.0 * c));
  }
  // 5 c as a decimal: the rest length of a spring at rest (|x_i - x_j| to rounding)
  double length() const { return decimal(5.0 * c); }
};

void stretched(const wbtest::Params& p) {
  // x_i = (1, 2), x_j = (4, 6): d = x_i - x_j = (-3, -4), L = 5, u = (-0.6, -0.8).
  // k = 10, rest = 2: tension k (L - rest) = 30, f_i = -30 u = (18, 24), along
  // x_j - x_i. Both ends move with the same velocity, so the damper adds nothing.
  const Ends e(p, Vec2(1, 2), 1.0);
  const Vec2 v(p.num(0.3, 0.1, 0.5), p.num(-0.7, -0.9, -0.5));
  const double k = p.num(10.0, 8.0, 12.0), rest = p.num(2.0, 1.5, 2.5), kd = p.num(0.5, 0.3, 0.7);
  const Vec2 expected = spring_law(e.xi, e.xj, v, v, k, rest, 0.0);
  const Vec2 fi = spring_force(e.xi, e.xj, v, v, k, rest, kd);
  wbtest::require_near(fi, expected, kTol,
                       p.held_out() ? "Hooke's law: a spring stretched by L - rest pulls end i "
                                      "towards j with k (L - rest)"
                                    : "Hooke's law: a spring stretched by L - rest = 3 pulls end "
                                      "i towards j with k (L - rest) = 30",
                       kTol);
  // The same spring seen from end j.
  const Vec2 fj = spring_force(e.xj, e.xi, v, v, k, rest, kd);
  wbtest::require_near(fj, Vec2(-expected), kTol,
                       "seen from the other end the spring pulls j towards i (f_j = -f_i)", kTol);
}

void compressed_and_at_rest(const wbtest::Params& p) {
  // Same ends as above (L = 5, u = (-0.6, -0.8)), k = 10.
  // rest = 7: tension 10 (5 - 7) = -20, f_i = 20 u = (-12, -16), away from j.
  // Held-out: the ends, k and rest drawn (rest > L).
  const Ends e(p, Vec2(1, 2), 1.0);
  const Vec2 zero(0, 0);
  const double k = p.num(10.0, 8.0, 12.0), rest = p.num(7.0, 6.6, 8.5);
  wbtest::require_near(spring_force(e.xi, e.xj, zero, zero, k, rest, 0.0),
                       spring_law(e.xi, e.xj, zero, zero, k, rest, 0.0), kTol,
                       p.held_out() ? "Hooke's law: a compressed spring pushes end i away "
                                      "from j with k (rest - L)"
                                    : "Hooke's law: a spring compressed by 2 pushes end i away "
                                      "from j with k (rest - L) = 20",
                       kTol);
  // rest = 5 = L: no force.
  wbtest::require_near(spring_force(e.xi, e.xj, zero, zero, k, e.length(), 0.0), Vec2(0, 0), kTol,
                       "a spring at its rest length exerts no force");
}

void minus_gradient(const wbtest::Params& p) {
  // Random ends 0.5 to 3 apart, random rest lengths, no damping. Central
  // differences, h = 1e-5: truncation h^2/6 |V'''| with |V'''| ~ 3 k / L < 100
  // here gives < 2e-9, rounding eps_mach |V| / h ~ 1e-16 * 50 / 1e-5 = 5e-10;
  // tolerance 1e-7. Held-out: the seeds of the ends (drawn again while fewer than 3 of the 6
  // springs are 0.5 long), the rest lengths' seed and k drawn.
  Mat2X a, b;
  for (int tries = 0; tries < 100; ++tries) {
    a = wbtest::random_points(6, std::uint64_t(p.count(5, 1, 1000000)), -1.5, 1.5);
    b = wbtest::random_points(6, std::uint64_t(p.count(6, 1, 1000000)), -1.5, 1.5);
    if (((a - b).colwise().norm().array() >= 0.5).count() >= 3) break;
  }
  const Mat2X r = wbtest::random_points(6, std::uint64_t(p.count(8, 1, 1000000)), 0.2, 2.0);
  const double k = p.num(13.0, 10.0, 16.0), h = 1e-5, tol = 1e-7;
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

void damper_along_spring(const wbtest::Params& p) {
  // x_i = (2, 1), x_j = (-1, -3): d = (3, 4), L = 5, u = (0.6, 0.8), perp = (-0.8, 0.6).
  // k = 7, kd = 2, v_j = (0.1, 0.2). Held-out: x_i, the length, v_j, k, kd and the two
  // speeds drawn; u and perp as published.
  const Ends e(p, Vec2(2, 1), -1.0);
  const Vec2 xi = e.xi, xj = e.xj, u(0.6, 0.8), perp(-0.8, 0.6);
  const Vec2 vj(p.num(0.1, -0.5, 0.5), p.num(0.2, -0.5, 0.5));
  const double k = p.num(7.0, 5.0, 9.0), kd = p.num(2.0, 1.5, 2.5), rest = e.length();
  const double along = p.num(1.5, 1.0, 2.0), across = p.num(2.0, 1.5, 2.5);

  // Ends separating at 1.5 m/s along u, spring at rest length (rest = 5):
  // f_i = -kd 1.5 u = -3 u = (-1.8, -2.4), resisting the separation.
  wbtest::require_near(
      spring_force(xi, xj, vj + along * u, vj, k, rest, kd), Vec2(-kd * along * u), kTol,
      "the damper resists the rate of stretch: f_i = -kd ((v_i - v_j) . u) u", kTol);

  // Relative velocity across the spring only: the length does not change,
  // so there is no damping force at all.
  wbtest::require_near(spring_force(xi, xj, vj + across * perp, vj, k, rest, kd), Vec2(0, 0),
                       kTol,
                       "a relative velocity perpendicular to the spring does not change its "
                       "length: no damping force",
                       kTol);

  // Both at once: only the component along u counts, same force as the first case.
  wbtest::require_near(spring_force(xi, xj, vj + along * u + across * perp, vj, k, rest, kd),
                       Vec2(-kd * along * u), kTol,
                       "only the component of v_i - v_j along the spring is damped", kTol);

  // Spring and damper together, rest = 4: tension 7 * 1 + 2 * 1.5 = 10, f_i = -10 u.
  // Held-out: rest = L - 0.5 to 1.5.
  const double shorter = decimal(rest - p.num(1.0, 0.5, 1.5));
  const Vec2 vi = vj + along * u + across * perp;
  wbtest::require_near(
      spring_force(xi, xj, vi, vj, k, shorter, kd), spring_law(xi, xj, vi, vj, k, shorter, kd),
      kTol, "spring and damper add along u: -(k (L - rest) + kd (v_i - v_j) . u) u", kTol);
}

void anchored_and_third_law(const wbtest::Params& p) {
  // Anchor (2, 1), x_i = (0.5, -1), v_i = (1, 2): d = (-1.5, -2), L = 2.5,
  // u = (-0.6, -0.8), (v_i - 0) . u = -2.2. k = 4, rest = 1, kd = 0.3:
  // tension 4 * 1.5 + 0.3 * (-2.2) = 5.34, f_i = -5.34 u = (3.204, 4.272).
  // Held-out: each drawn about it.
  const Vec2 anchor(p.num(2.0, 1.5, 2.5), p.num(1.0, 0.5, 1.5)),
      xi(p.num(0.5, 0.0, 1.0), p.num(-1.0, -1.5, -0.5)),
      vi(p.num(1.0, 0.5, 1.5), p.num(2.0, 1.5, 2.5));
  const double k = p.num(4.0, 3.0, 5.0), rest = p.num(1.0, 0.5, 1.5), kd = p.num(0.3, 0.1, 0.5);
  wbtest::require_near(spring_force(xi, anchor, vi, Vec2(0, 0), k, rest, kd),
                       spring_law(xi, anchor, vi, Vec2(0, 0), k, rest, kd), kTol,
                       "spring to a fixed anchor (x_j = anchor, v_j = 0)", kTol);

  // Between two particles the forces on the two ends cancel (third law), so a
  // free spring does not change the total momentum. Held-out: the seeds, k, rest and kd drawn.
  const Mat2X x = wbtest::random_points(8, std::uint64_t(p.count(21, 1, 1000000)), -2.0, 2.0);
  const Mat2X v = wbtest::random_points(8, std::uint64_t(p.count(22, 1, 1000000)), -1.0, 1.0);
  const double k2 = p.num(5.0, 3.0, 7.0), rest2 = p.num(0.7, 0.4, 1.0),
               kd2 = p.num(0.4, 0.2, 0.6);
  for (Eigen::Index s = 0; s + 1 < 8; s += 2) {
    CAPTURE(s);
    const Vec2 fi = spring_force(x.col(s), x.col(s + 1), v.col(s), v.col(s + 1), k2, rest2, kd2);
    const Vec2 fj = spring_force(x.col(s + 1), x.col(s), v.col(s + 1), v.col(s), k2, rest2, kd2);
    wbtest::require_near(Vec2(fi + fj), Vec2(0, 0), 1e-12 * (1 + fi.norm()),
                         "Newton's third law: f_j = -f_i for a spring between two particles");
  }
}

void zero_length(const wbtest::Params& p) {
  // Both ends at (1.5, -0.5), rest = 0.8: the direction u is undefined and
  // the header says return (0, 0). Held-out: each drawn about it.
  const Vec2 x0(p.num(1.5, 1.0, 2.0), p.num(-0.5, -1.0, 0.0)),
      vi(p.num(1.0, 0.5, 1.5), p.num(0.0, -0.3, 0.3)),
      vj(p.num(0.0, -0.3, 0.3), p.num(1.0, 0.5, 1.5));
  const double k = p.num(10.0, 8.0, 12.0), rest = p.num(0.8, 0.6, 1.0), kd = p.num(1.0, 0.5, 1.5);
  const Vec2 f0 = spring_force(x0, x0, vi, vj, k, rest, kd);
  {
    INFO("zero-length spring gave " << wbtest::str(f0));
    REQUIRE(f0.allFinite());
  }
  wbtest::require_near(f0, Vec2(0, 0), 0.0, "L == 0: no direction, so no force (header)");

  // The same spring with x_j = x_i + (0.3, 0.4): d = (-0.3, -0.4), L = 0.5,
  // u = (-0.6, -0.8), (v_i - v_j) . u = (1, -1) . u = 0.2:
  // tension 10 (0.5 - 0.8) + 1 * 0.2 = -2.8, f_i = 2.8 u = (-1.68, -2.24).
  // Held-out: the offset c (0.3, 0.4), c from 0.7 to 1.3.
  const double c = p.num(1.0, 0.7, 1.3);
  const Vec2 xj = x0 + c * Vec2(0.3, 0.4);
  wbtest::require_near(spring_force(x0, xj, vi, vj, k, rest, kd),
                       spring_law(x0, xj, vi, vj, k, rest, kd), kTol,
                       "a short compressed damped spring pushes i away from j", kTol);
}

// The held-out test's own case (no public test makes it): 4 springs, the first of zero length,
// every end, velocity, k, rest and kd a short decimal drawn in the public tests' ranges.
void random_springs(const wbtest::Params& p) {
  for (int s = 0; s < 4; ++s) {
    const Vec2 xi(p.num(0, -3.0, 3.0), p.num(0, -3.0, 3.0)),
        vi(p.num(0, -2.0, 2.0), p.num(0, -2.0, 2.0)),
        vj(p.num(0, -2.0, 2.0), p.num(0, -2.0, 2.0));
    const Vec2 xj = s == 0 ? xi : Vec2(p.num(0, -3.0, 3.0), p.num(0, -3.0, 3.0));
    const double k = p.num(1.0, 1.0, 15.0), rest = p.num(1.0, 0.2, 4.0), kd = p.num(0, 0.0, 2.0);
    INFO("x_i = " << wbtest::str(xi) << ", x_j = " << wbtest::str(xj)
                  << ", v_i = " << wbtest::str(vi) << ", v_j = " << wbtest::str(vj)
                  << ", k = " << k << ", rest = " << rest << ", kd = " << kd);
    const Vec2 expected = spring_law(xi, xj, vi, vj, k, rest, kd);
    wbtest::require_near(spring_force(xi, xj, vi, vj, k, rest, kd), expected,
                         1e-12 * (1.0 + expected.norm()),
                         "spring-damper f_i = -(k (L - rest) + kd (v_i - v_j) . u) u, "
                         "u = (x_i - x_j) / L, zero when L = 0",
                         1e-12);
  }
}

}  // namespace

TEST_CASE("F5 spring: a stretched spring pulls i towards j with k (L - rest)",
          "[forces][F5][3pts]") {
  stretched(wbtest::Params());
}

TEST_CASE("F5 spring: a compressed spring pushes apart and a spring at rest length does nothing",
          "[forces][F5][2pts]") {
  compressed_and_at_rest(wbtest::Params());
}

TEST_CASE("F5 spring: the spring force is minus the gradient of 1/2 k (L - rest)^2",
          "[forces][F5][2pts]") {
  minus_gradient(wbtest::Params());
}

TEST_CASE("F5 spring: the damper acts only along the spring", "[forces][F5][3pts]") {
  damper_along_spring(wbtest::Params());
}

TEST_CASE("F5 spring: anchored form and equal and opposite forces between particles",
          "[forces][F5][1pts]") {
  anchored_and_third_law(wbtest::Params());
}

TEST_CASE("F5 spring: a zero-length spring returns zero and no NaN", "[forces][F5][2pts]") {
  zero_length(wbtest::Params());
}

// Every public scenario above again, its parameters drawn from the held-out seed in the public
// tests' format, and random springs of its own in the same format, so that no call tells the
// public tests from this one (tools/adversary --inputs).
TEST_CASE("F5 held-out: random springs give f_i = -(k (L - rest) + kd (v_i - v_j) . u) u",
          "[forces][F5][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F5")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    stretched(p);
    compressed_and_at_rest(p);
    minus_gradient(p);
    damper_along_spring(p);
    anchored_and_third_law(p);
    zero_length(p);
    random_springs(p);
  }
}

}  // namespace test_F5_spring
