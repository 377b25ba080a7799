// Graded tests for TODO(R4), the position and orientation update
// (labs/rigid/integrate_position.cpp). Expected values: rotations about a fixed
// axis compose by adding angles, and rotation matrices are orthonormal.
#include <cmath>

#include "integrate_position.h"
#include "rigid_kernels.h"
#include "rigid_test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_R4_integrate_position {

using namespace rigidtest;

namespace {

// n = 1000 compositions of unit quaternions: rounding grows like n * eps, and the
// reference's cos and sin of 1000 rad carry ~1e-13.
constexpr double kComposeTol = 1e-11;
// The bound on |R^T R - E| and |det R - 1| after 10^6 steps.
constexpr double kOrthoTol = 1e-12;
// Two exact exponential maps written differently drift apart by rounding only:
// ~1e-16 per step, a random walk over 10^6 steps stays far below this.
constexpr double kSameMotionTol = 1e-6;

double orthonormality_error(const Mat3& R) {
  return std::max((R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff(),
                  std::abs(R.determinant() - 1.0));
}

}  // namespace

TEST_CASE("R4 constant omega: after n steps the body has turned by n h |omega| about omega",
          "[rigid][R4][4pts]") {
  // A slow turn (omega h = 0.02 rad per step) and a fast spin (omega h = 1 rad per step).
  for (double speed : {2.0, 100.0}) {
    INFO("|omega| = " << speed << " rad/s");
    const Eigen::Quaterniond q0 = quat(0.6, 0.2, -0.5, 0.3);
    const Vec3 w = speed * Vec3(0.4, -1.1, 2.0).normalized(), v(1.0, -0.5, 2.0),
               x0(0.1, 0.2, 0.3);
    Body b = make_body(1.5, Vec3(1, 2, 3), q0, w, x0, v);
    const double h = 0.01;
    const int n = 1000;
    for (int k = 0; k < n; ++k) integrate_position(b, h);
    // Rotations about one fixed (world) axis add their angles; the world-frame omega
    // turns the body AFTER its current orientation: R_n = Rot(n h |w|, w) R_0.
    const Mat3 expected = Eigen::AngleAxisd(n * h * w.norm(), w.normalized()).toRotationMatrix() *
                          q0.toRotationMatrix();
    require_near(
        rot(b), expected, kComposeTol,
        "R after n steps = rotation by n h |omega| about omega (world frame), times R_0");
    require_near(b.x, Vec3(x0 + n * h * v), kComposeTol, "x after n steps = x0 + n h v",
                 kComposeTol);
    require_near(b.omega, w, 0.0, "omega is not changed by the position update");
  }
}

TEST_CASE(
    "R4 omega zero or along a principal axis: no NaN from a zero angle and the centre moves",
    "[rigid][R4][3pts]") {
  const Eigen::Quaterniond q0 = quat(0.9, 0.1, 0.3, -0.2);
  Body b = make_body(1.0, Vec3(1, 2, 3), q0, Vec3::Zero(), Vec3::Zero(), Vec3(0.0, 3.0, 0.0));
  integrate_position(b, 0.5);
  REQUIRE(b.q.coeffs().allFinite());
  require_near(rot(b), q0.toRotationMatrix(), kComposeTol, "omega = 0: the orientation stays");
  require_near(b.x, Vec3(0.0, 1.5, 0.0), kComposeTol, "x = x0 + h v");
  // A spin exactly along the body's first axis: the axis does not move.
  Body s = make_body(1.0, Vec3(1, 2, 3), q0, Vec3(5.0 * q0.toRotationMatrix().col(0)));
  for (int k = 0; k < 100; ++k) integrate_position(s, 0.01);
  REQUIRE(s.q.coeffs().allFinite());
  require_near(Vec3(rot(s).col(0)), Vec3(q0.toRotationMatrix().col(0)), kComposeTol,
               "spinning about its own axis 0, the body's axis 0 stays where it was");
}

TEST_CASE("R4 R stays orthonormal with det R = 1 after a million steps", "[rigid][R4][5pts]") {
  Body b = make_body(1.0, Vec3(1, 2, 3), quat(0.5, 0.5, -0.5, 0.5), Vec3::Zero());
  Body ref = b;  // the same motion by the test's own exponential map
  const double h = 1e-3;
  // A tumbling motion: omega changes direction all the time (rigid_kernels.h). The student's
  // steps run as one call (rigid_tumble_run), the reference's here.
  rigid_tumble_run(b, h, 1000000);
  for (long k = 0; k < 1000000; ++k) {
    ref.omega = tumble_omega(double(k) * h);
    ref_position(ref, h);
  }
  require_near(rot(b), rot(ref), kSameMotionTol,
               "after 10^6 steps the body has turned as the exponential map turns it");
  REQUIRE(b.q.coeffs().allFinite());
  const double err = orthonormality_error(rot(b));
  INFO("max(|R^T R - E|, |det R - 1|) after 10^6 steps = " << err << ", expected <= " << kOrthoTol
                                                           << " (renormalise q every step)");
  REQUIRE(err <= kOrthoTol);
  INFO("|q| after 10^6 steps = " << b.q.norm());
  REQUIRE(std::abs(b.q.norm() - 1.0) <= kOrthoTol);
}

}  // namespace test_R4_integrate_position
