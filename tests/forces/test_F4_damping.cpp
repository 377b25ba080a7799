// F4 viscous damping: f_i += -b v_i (labs/forces/damping.h).
#include "damping.h"
#include "heldout.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F4_damping {

using wb::Mat2X;
using wb::Vec2;

namespace {
// Products of short decimals: rounding only.
constexpr double kTol = 1e-12;
}  // namespace

TEST_CASE("F4 damping: f = -b v opposes the velocity with magnitude b |v|",
          "[forces][F4][2pts]") {
  // b = 0.7. v_0 = (3, -4): f_0 = (-2.1, 2.8), |f_0| = 0.7 * 5 = 3.5.
  // v_1 = (-0.5, 2):  f_1 = (0.35, -1.4). v_2 = 0: no force.
  // (The drag does not involve the mass: the same b for every particle.)
  Mat2X v(2, 3);
  v << 3.0, -0.5, 0.0,  //
      -4.0, 2.0, 0.0;
  Mat2X f = Mat2X::Zero(2, 3);
  add_damping(v, 0.7, f);
  Mat2X expected(2, 3);
  expected << -2.1, 0.35, 0.0,  //
      2.8, -1.4, 0.0;
  wbtest::require_near(f, expected, kTol, "viscous drag: f = -b v, against the motion", kTol);
}

TEST_CASE("F4 damping: adds to the forces already there", "[forces][F4][2pts]") {
  Mat2X v(2, 2);
  v << 1.0, 0.0,  //
      2.0, -3.0;
  Mat2X f(2, 2);
  f << 5.0, -1.0,  //
      6.0, 0.25;
  add_damping(v, 0.5, f);
  // previous - 0.5 v: (5 - 0.5, 6 - 1) and (-1 - 0, 0.25 + 1.5)
  Mat2X expected(2, 2);
  expected << 4.5, -1.0,  //
      5.0, 1.75;
  wbtest::require_near(f, expected, kTol,
                       "forces add up (superposition): f must keep what other terms put there",
                       kTol);
}

TEST_CASE("F4 damping: the drag removes energy at the rate b |v|^2", "[forces][F4][1pts]") {
  // Power of the drag on each particle: f . v = -b |v|^2 <= 0 (it only dissipates).
  const Mat2X v = wbtest::random_points(5, 99, -2.0, 2.0);
  const double b = 1.25;
  Mat2X f = Mat2X::Zero(2, 5);
  add_damping(v, b, f);
  for (Eigen::Index i = 0; i < 5; ++i) {
    CAPTURE(i);
    const Vec2 vi = v.col(i);
    wbtest::require_near(Vec2(f.col(i)).dot(vi), -b * vi.squaredNorm(), kTol,
                         "power of viscous drag: f . v = -b |v|^2", kTol);
  }
}

TEST_CASE("F4 held-out: random velocities get f_i += -b v_i", "[forces][F4][held-out][1pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F4")) {
    INFO(g.replay());
    const Eigen::Index n = g.integer(3, 9);
    const Mat2X v = g.points(n, -10.0, 10.0), f0 = g.points(n, -20.0, 20.0);
    const double b = g.uniform(0.05, 5.0);
    Mat2X f = f0;
    add_damping(v, b, f);
    INFO("b = " << b << ", v = " << v << "\n  f before = " << f0);
    wbtest::require_near(f, Mat2X(f0 - b * v), kTol, "viscous drag f_i += -b v_i", kTol);
  }
}

}  // namespace test_F4_damping
