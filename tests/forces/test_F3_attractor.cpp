// F3 attractor: f_i += -GM m_i d_i / |d_i|^3, d_i = x_i - center
// (labs/forces/attractor.h).
#include <cmath>

#include "attractor.h"
#include "heldout.h"
#include "params.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F3_attractor {

using wb::Mat2X;
using wb::Vec2;
using wb::VecX;

namespace {
// Hand-derived values (published) or the law computed here from short decimals, every
// particle at least 0.7 from the centre: rounding only.
constexpr double kTol = 1e-12;

// -GM m_i d_i / |d_i|^3 added to f0, nothing for a particle at the centre (the law, written
// out here).
Mat2X attractor_law(const Mat2X& x, const VecX& m, const Vec2& c, double GM, const Mat2X& f0) {
  Mat2X f = f0;
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const Vec2 d = x.col(i) - c;
    const double r = d.norm();
    if (r > 0.0) f.col(i) -= GM * m[i] * d / (r * r * r);
  }
  return f;
}

// The scenarios of the public tests below, each a function of its parameters: the public test
// runs it with the published ones (wbtest::Params()), the held-out test with drawn ones, in the
// same format (tests/common/params.h): short decimals, the published particle counts, about
// the published magnitudes.

// The published centre, GM and particle 0 of the first test: c = (1, -2), GM = 3,
// x_0 = (4, 2), m_0 = 2 (d = (3, 4), r = 5). Held-out: each drawn about it.
struct Published {
  Vec2 c, x0;
  double GM, m0;
  explicit Published(const wbtest::Params& p)
      : c(p.num(1.0, 0.5, 1.5), p.num(-2.0, -2.5, -1.5)),
        x0(p.num(4.0, 3.0, 5.0), p.num(2.0, 1.0, 3.0)),
        GM(p.num(3.0, 2.0, 4.0)),
        m0(p.num(2.0, 1.0, 3.0)) {}
};

void off_origin(const wbtest::Params& p) {
  // center (1, -2), GM = 3.
  // Particle 0 at (4, 2): d = (3, 4), r = 5, r^3 = 125, m = 2:
  //   f_0 = -3 * 2 (3, 4) / 125 = (-0.144, -0.192).
  // Particle 1 at (-0.2, -1.5): d = (-1.2, 0.5), r = 1.3, r^3 = 2.197, m = 0.5:
  //   f_1 = -3 * 0.5 (-1.2, 0.5) / 2.197 = (1.8, -0.75) / 2.197.
  // Held-out: particle 1 drawn about (-0.2, -1.5), at least 0.7 from the centre.
  const Published q(p);
  Mat2X x(2, 2);
  x.col(0) = q.x0;
  x.col(1) = Vec2(p.num(-0.2, -0.6, 0.0), p.num(-1.5, -1.0, -0.5));
  VecX m(2);
  m << q.m0, p.num(0.5, 0.2, 0.9);
  Mat2X f = Mat2X::Zero(2, 2);
  add_attractor(x, m, q.c, q.GM, f);
  const Mat2X expected = attractor_law(x, m, q.c, q.GM, Mat2X::Zero(2, 2));
  wbtest::require_near(Vec2(f.col(0)), Vec2(expected.col(0)), kTol,
                       "inverse-square pull towards the centre: |f| = GM m / r^2 along -d/r",
                       kTol);
  wbtest::require_near(Vec2(f.col(1)), Vec2(expected.col(1)), kTol,
                       "inverse-square pull towards the centre: |f| = GM m / r^2 along -d/r",
                       kTol);
}

void adds_up(const wbtest::Params& p) {
  // Particle 0 of the first test: (-0.144, -0.192) on top of (1, 2): (0.856, 1.808).
  const Published q(p);
  const Mat2X x = q.x0;
  VecX m(1);
  m << q.m0;
  Mat2X f(2, 1);
  f << p.num(1.0, 0.5, 1.5), p.num(2.0, 1.5, 2.5);
  const Mat2X f0 = f;
  add_attractor(x, m, q.c, q.GM, f);
  wbtest::require_near(Vec2(f.col(0)), Vec2(attractor_law(x, m, q.c, q.GM, f0).col(0)), kTol,
                       "forces add up (superposition): f must keep what other terms put there",
                       kTol);
}

void minus_gradient(const wbtest::Params& p) {
  // Three particles 0.7 to 2.3 from the centre (held-out: the centre and each coordinate
  // within 0.1 of the published ones, so 0.5 to 2.5). Central differences, h = 1e-5:
  // truncation h^2/6 |V'''| <= 1e-10 / 6 * 6 GM m / r^4 < 1e-8 here,
  // rounding eps_mach |V| / h ~ 1e-16 * 10 / 1e-5 = 1e-10; tolerance 1e-7.
  const Vec2 c(p.num(-0.5, -0.6, -0.4), p.num(0.25, 0.15, 0.35));
  Mat2X x(2, 3);
  x << p.num(0.2, 0.1, 0.3), p.num(-1.9, -2.0, -1.8), p.num(1.3, 1.2, 1.4),  //
      p.num(0.35, 0.25, 0.45), p.num(1.0, 0.9, 1.1), p.num(-1.1, -1.2, -1.0);
  VecX m(3);
  m << p.num(1.5, 1.0, 2.0), p.num(0.3, 0.1, 0.6), p.num(2.2, 1.8, 2.6);
  const double GM = p.num(0.8, 0.5, 1.2), h = 1e-5, tol = 1e-7;
  auto V = [&](const Mat2X& y) {
    double sum = 0;
    for (Eigen::Index i = 0; i < y.cols(); ++i) sum -= GM * m[i] / (y.col(i) - c).norm();
    return sum;
  };
  const Mat2X expected = wbtest::minus_gradient(V, x, h);
  Mat2X f = Mat2X::Zero(2, 3);
  add_attractor(x, m, c, GM, f);
  wbtest::require_near(f, expected, tol, "the attractor is conservative: f = -dV/dx", tol);
}

void at_centre(const wbtest::Params& p) {
  // Particle 0 sits on the centre (1, -2); particle 1 is the first test's
  // particle 0: f_1 = (-0.144, -0.192).
  const Published q(p);
  Mat2X x(2, 2);
  x.col(0) = q.c;
  x.col(1) = q.x0;
  VecX m(2);
  m << p.num(1.0, 0.5, 1.5), q.m0;
  Mat2X f = Mat2X::Zero(2, 2);
  add_attractor(x, m, q.c, q.GM, f);
  wbtest::require_finite(f, "attractor with a particle at the centre");
  wbtest::require_near(Vec2(f.col(0)), Vec2::Zero(), 0.0,
                       "at the centre the direction is undefined: the header says no force");
  wbtest::require_near(Vec2(f.col(1)),
                       Vec2(attractor_law(x, m, q.c, q.GM, Mat2X::Zero(2, 2)).col(1)), kTol,
                       "the other particle is still pulled with GM m / r^2", kTol);
}

// The held-out test's own case (no public test makes it): 1 to 3 particles, the last at least
// 1 from the centre, one of the others (when there are) exactly at it; the centre, GM, every
// mass, position and force already there drawn in the public tests' ranges and format.
void random_particles(const wbtest::Params& p) {
  const Eigen::Index n = p.count(2, 1, 3);
  const Vec2 c(p.num(0.0, -2.0, 2.0), p.num(0.0, -2.0, 2.0));
  const double GM = p.num(1.0, 0.5, 4.0);
  Mat2X x(2, n), f0(2, n);
  VecX m(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    // a direction and a distance 1 to 4 from the centre, written as short decimals
    const double a = p.num(0.0, 0.0, 6.28), r = p.num(2.0, 1.0, 4.0);
    x.col(i) = Vec2(wbtest::Params::short_decimal(c.x() + r * std::cos(a)),
                    wbtest::Params::short_decimal(c.y() + r * std::sin(a)));
    m[i] = p.num(1.0, 0.2, 3.0);
    f0.col(i) = Vec2(p.num(0.0, -2.0, 2.0), p.num(0.0, -2.0, 2.0));
  }
  if (n > 1) x.col(p.count(0, 0, n - 2)) = c;  // exactly at the centre: no force, no NaN
  Mat2X f = f0;
  add_attractor(x, m, c, GM, f);
  INFO("center " << wbtest::str(c) << ", GM = " << GM << ", x = " << x
                 << "\n  m = " << m.transpose());
  wbtest::require_near(f, attractor_law(x, m, c, GM, f0), kTol,
                       "f_i += -GM m_i (x_i - c) / |x_i - c|^3 (nothing at the centre itself)",
                       kTol);
}

}  // namespace

TEST_CASE("F3 attractor: pull of -GM m_i d_i / r^3 towards a centre off the origin",
          "[forces][F3][3pts]") {
  off_origin(wbtest::Params());
}

TEST_CASE("F3 attractor: adds to the forces already there", "[forces][F3][1pts]") {
  adds_up(wbtest::Params());
}

TEST_CASE("F3 attractor: the force is minus the gradient of V = -sum GM m_i / r_i",
          "[forces][F3][2pts]") {
  minus_gradient(wbtest::Params());
}

TEST_CASE("F3 attractor: a particle exactly at the centre gets no force and no NaN",
          "[forces][F3][2pts]") {
  at_centre(wbtest::Params());
}

// Every public scenario above again, its parameters drawn from the held-out seed in the public
// tests' format, and a case of its own in the same format, so that no call tells the public
// tests from this one (tools/adversary --inputs).
TEST_CASE("F3 held-out: random particles are pulled with -GM m_i d_i / r_i^3",
          "[forces][F3][held-out][1pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F3")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    off_origin(p);
    adds_up(p);
    minus_gradient(p);
    at_centre(p);
    random_particles(p);
  }
}

}  // namespace test_F3_attractor
