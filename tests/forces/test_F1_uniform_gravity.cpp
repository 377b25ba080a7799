// F1 uniform gravity: f_i += m_i g (labs/forces/uniform_gravity.h).
#include "heldout.h"
#include "test_helpers.h"
#include "uniform_gravity.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F1_uniform_gravity {

using wb::Mat2X;
using wb::Vec2;
using wb::VecX;

namespace {
// Sums of a few products of short decimals: rounding only.
constexpr double kTol = 1e-12;
}  // namespace

TEST_CASE("F1 uniform gravity: each particle gets m_i g", "[forces][F1][2pts]") {
  // Distinct masses (one below 1, so m^2 != m) and a g with both components
  // non-zero and different, so a missing or squared mass or swapped x/y shows.
  VecX m(3);
  m << 0.5, 2.0, 3.0;
  const Vec2 g(1.5, -9.81);
  Mat2X f = Mat2X::Zero(2, 3);
  add_uniform_gravity(m, g, f);
  // m_i g: (0.75, -4.905), (3, -19.62), (4.5, -29.43)
  Mat2X expected(2, 3);
  expected << 0.75, 3.0, 4.5,  //
      -4.905, -19.62, -29.43;
  wbtest::require_near(f, expected, kTol, "uniform gravity: f_i = m_i g (weight is mass times g)",
                       kTol);
  INFO("f keeps one column per particle (3); got " << f.cols()
                                                   << ": add into f, never resize it");
  REQUIRE(f.cols() == 3);
}

TEST_CASE("F1 uniform gravity: adds to the forces already there", "[forces][F1][2pts]") {
  VecX m(2);
  m << 0.25, 4.0;
  const Vec2 g(-2.0, 8.0);
  Mat2X f(2, 2);
  f << 10.0, -3.0,  //
      7.0, 0.5;
  add_uniform_gravity(m, g, f);
  // previous + m_i g: (10 - 0.5, 7 + 2) and (-3 - 8, 0.5 + 32)
  Mat2X expected(2, 2);
  expected << 9.5, -11.0,  //
      9.0, 32.5;
  wbtest::require_near(f, expected, kTol,
                       "forces add up (superposition): f must keep what other terms put there",
                       kTol);
}

TEST_CASE("F1 uniform gravity: the force is minus the gradient of V = -sum m_i g . x_i",
          "[forces][F1][2pts]") {
  VecX m(3);
  m << 1.5, 0.2, 2.5;
  const Vec2 g(0.3, -9.81);
  const Mat2X x = wbtest::random_points(3, 11, -2.0, 2.0);
  auto V = [&](const Mat2X& y) { return -(g.transpose() * y).dot(m); };
  // V is linear in x, so central differences are exact up to rounding:
  // about eps_mach |V| / h = 1e-16 * 100 / 1e-3, far under the tolerance.
  const double h = 1e-3, tol = 1e-9;
  const Mat2X expected = wbtest::minus_gradient(V, x, h);
  Mat2X f = Mat2X::Zero(2, 3);
  add_uniform_gravity(m, g, f);
  wbtest::require_near(f, expected, tol, "gravity is conservative: f = -dV/dx", tol);
}

TEST_CASE("F1 held-out: random particles get f_i += m_i g", "[forces][F1][held-out][1pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F1")) {
    INFO(g.replay());
    const Eigen::Index n = g.integer(3, 9);
    const VecX m = g.values(n, 0.1, 5.0);
    const Vec2 grav = g.vec2(-20.0, 20.0);
    const Mat2X f0 = g.points(n, -50.0, 50.0);  // forces already there
    Mat2X f = f0;
    add_uniform_gravity(m, grav, f);
    Mat2X expected = f0;
    for (Eigen::Index i = 0; i < n; ++i) expected.col(i) += m[i] * grav;
    INFO("m = " << m.transpose() << ", g = " << wbtest::str(grav) << ", f before = " << f0);
    wbtest::require_near(f, expected, kTol, "uniform gravity: f_i += m_i g", kTol);
  }
}

}  // namespace test_F1_uniform_gravity
