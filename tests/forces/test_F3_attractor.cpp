// F3 attractor: f_i += -GM m_i d_i / |d_i|^3, d_i = x_i - center
// (labs/forces/attractor.h).
#include <cmath>

#include "attractor.h"
#include "heldout.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F3_attractor {

using wb::Mat2X;
using wb::Vec2;
using wb::VecX;

namespace {
// Hand-derived values below are exact decimals or short quotients: rounding only.
constexpr double kTol = 1e-12;
}  // namespace

TEST_CASE("F3 attractor: pull of -GM m_i d_i / r^3 towards a centre off the origin",
          "[forces][F3][3pts]") {
  // center (1, -2), GM = 3.
  // Particle 0 at (4, 2): d = (3, 4), r = 5, r^3 = 125, m = 2:
  //   f_0 = -3 * 2 (3, 4) / 125 = (-0.144, -0.192).
  // Particle 1 at (-0.2, -1.5): d = (-1.2, 0.5), r = 1.3, r^3 = 2.197, m = 0.5:
  //   f_1 = -3 * 0.5 (-1.2, 0.5) / 2.197 = (1.8, -0.75) / 2.197.
  const Vec2 c(1, -2);
  Mat2X x(2, 2);
  x << 4.0, -0.2,  //
      2.0, -1.5;
  VecX m(2);
  m << 2.0, 0.5;
  Mat2X f = Mat2X::Zero(2, 2);
  add_attractor(x, m, c, 3.0, f);
  wbtest::require_near(Vec2(f.col(0)), Vec2(-0.144, -0.192), kTol,
                       "inverse-square pull towards the centre: |f| = GM m / r^2 along -d/r",
                       kTol);
  wbtest::require_near(Vec2(f.col(1)), Vec2(1.8 / 2.197, -0.75 / 2.197), kTol,
                       "inverse-square pull towards the centre: |f| = GM m / r^2 along -d/r",
                       kTol);
}

TEST_CASE("F3 attractor: adds to the forces already there", "[forces][F3][1pts]") {
  // Particle 0 of the first test: (-0.144, -0.192) on top of (1, 2).
  Mat2X x(2, 1);
  x << 4.0, 2.0;
  VecX m(1);
  m << 2.0;
  Mat2X f(2, 1);
  f << 1.0, 2.0;
  add_attractor(x, m, Vec2(1, -2), 3.0, f);
  wbtest::require_near(Vec2(f.col(0)), Vec2(0.856, 1.808), kTol,
                       "forces add up (superposition): f must keep what other terms put there",
                       kTol);
}

TEST_CASE("F3 attractor: the force is minus the gradient of V = -sum GM m_i / r_i",
          "[forces][F3][2pts]") {
  // Three particles 0.7 to 2.3 from the centre. Central differences, h = 1e-5:
  // truncation h^2/6 |V'''| <= 1e-10 / 6 * 6 GM m / r^4 < 1e-9 here,
  // rounding eps_mach |V| / h ~ 1e-16 * 10 / 1e-5 = 1e-10; tolerance 1e-7.
  const Vec2 c(-0.5, 0.25);
  Mat2X x(2, 3);
  x << 0.2, -1.9, 1.3,  //
      0.35, 1.0, -1.1;
  VecX m(3);
  m << 1.5, 0.3, 2.2;
  const double GM = 0.8, h = 1e-5, tol = 1e-7;
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

TEST_CASE("F3 attractor: a particle exactly at the centre gets no force and no NaN",
          "[forces][F3][2pts]") {
  // Particle 0 sits on the centre (1, -2); particle 1 is the first test's
  // particle 0: f_1 = (-0.144, -0.192).
  Mat2X x(2, 2);
  x << 1.0, 4.0,  //
      -2.0, 2.0;
  VecX m(2);
  m << 1.0, 2.0;
  Mat2X f = Mat2X::Zero(2, 2);
  add_attractor(x, m, Vec2(1, -2), 3.0, f);
  wbtest::require_finite(f, "attractor with a particle at the centre");
  wbtest::require_near(Vec2(f.col(0)), Vec2::Zero(), 0.0,
                       "at the centre the direction is undefined: the header says no force");
  wbtest::require_near(Vec2(f.col(1)), Vec2(-0.144, -0.192), kTol,
                       "the other particle is still pulled with GM m / r^2", kTol);
}

TEST_CASE("F3 held-out: random particles are pulled with -GM m_i d_i / r_i^3",
          "[forces][F3][held-out][1pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F3")) {
    INFO(g.replay());
    const Eigen::Index n = g.integer(3, 9);
    const Vec2 c = g.vec2(-2.0, 2.0);
    Mat2X x = g.points(n, -4.0, 4.0);
    x.col(g.integer(0, n - 2)) = c;  // one exactly at the centre (not the last): no force, no NaN
    const VecX m = g.values(n, 0.1, 4.0);
    const double GM = g.uniform(0.2, 5.0);
    const Mat2X f0 = g.points(n, -5.0, 5.0);
    Mat2X f = f0;
    add_attractor(x, m, c, GM, f);
    Mat2X expected = f0;
    double scale = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Vec2 d = x.col(i) - c;
      const double r = d.norm();
      if (r == 0.0) continue;
      expected.col(i) -= GM * m[i] * d / (r * r * r);
      scale += GM * m[i] / (r * r);
    }
    INFO("center " << wbtest::str(c) << ", GM = " << GM << ", x = " << x
                   << "\n  m = " << m.transpose());
    wbtest::require_near(f, expected, 1e-12 * (1.0 + scale),
                         "f_i += -GM m_i (x_i - c) / |x_i - c|^3 (nothing at the centre itself)",
                         1e-12);
  }
}

}  // namespace test_F3_attractor
