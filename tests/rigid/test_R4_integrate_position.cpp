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
// The handout's bound on |R^T R - E| and |det R - 1| after 10^6 steps. Without
// renormalisation, |q| drifts steadily under a constant omega (the same rounding
// of |dq| every step): ~1e-11 after 10^6 steps, R^T R - E ~1e-10.
constexpr double kOrthoTol = 1e-12;
// The angle n h |omega| = 6164 rad after 10^6 steps, accumulated with ~1e-16 of
// rounding per step and the reference's cos and sin of it: far below this.
constexpr double kSameMotionTol = 1e-6;

double orthonormality_error(const Mat3& R) {
  // NaN-safe (wbtest::max_abs_diff, worst_of): a NaN anywhere makes the error infinite.
  return wbtest::worst_of(wbtest::max_abs_diff(Mat3(R.transpose() * R), Mat3::Identity()),
                          std::abs(R.determinant() - 1.0));
}

}  // namespace

TEST_CASE("R4 constant omega: after n steps the body has turned by n h |omega| about omega",
          "[rigid][R4][3pts]") {
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
  INFO("omega = 0: q = " << b.q.coeffs().transpose()
                         << ", expected finite: the rotation by a zero angle is the identity "
                            "(do not divide by |omega| when it is 0)");
  REQUIRE(b.q.coeffs().allFinite());
  require_near(rot(b), q0.toRotationMatrix(), kComposeTol, "omega = 0: the orientation stays");
  require_near(b.x, Vec3(0.0, 1.5, 0.0), kComposeTol, "x = x0 + h v");
  // A tiny omega (1e-10 rad/s) is not zero: over 1000 steps of 1 s the body turns
  // by 1e-7 rad, which the comparison sees (a threshold on |omega| would not turn it).
  const Vec3 tiny = 1e-10 * Vec3(0.6, 0.0, -0.8);
  Body t = make_body(1.0, Vec3(1, 2, 3), q0, tiny);
  for (int k = 0; k < 1000; ++k) integrate_position(t, 1.0);
  INFO("q after 1000 steps at omega = 1e-10 rad/s: " << t.q.coeffs().transpose()
                                                     << ", expected finite");
  REQUIRE(t.q.coeffs().allFinite());
  require_near(rot(t),
               Mat3(Eigen::AngleAxisd(1000 * tiny.norm(), tiny.normalized()).toRotationMatrix() *
                    q0.toRotationMatrix()),
               kComposeTol,
               "omega = 1e-10 rad/s for 1000 s: turned by 1e-7 rad (only omega = 0 exactly "
               "means no turn)");
  // A spin exactly along the body's first axis: the axis does not move.
  Body s = make_body(1.0, Vec3(1, 2, 3), q0, Vec3(5.0 * q0.toRotationMatrix().col(0)));
  for (int k = 0; k < 100; ++k) integrate_position(s, 0.01);
  INFO("spin along a principal axis, 100 steps: q = " << s.q.coeffs().transpose()
                                                      << ", expected finite");
  REQUIRE(s.q.coeffs().allFinite());
  require_near(Vec3(rot(s).col(0)), Vec3(q0.toRotationMatrix().col(0)), kComposeTol,
               "spinning about its own axis 0, the body's axis 0 stays where it was");
}

TEST_CASE("R4 R stays orthonormal with det R = 1 after a million steps", "[rigid][R4][4pts]") {
  // A constant omega: every step multiplies by the same dq, so whatever rounding
  // |dq| carries adds up steadily instead of averaging out (a changing omega
  // would hide a missing renormalisation).
  const Eigen::Quaterniond q0 = quat(0.5, 0.5, -0.5, 0.5);
  const Vec3 w(3.0, -2.0, 5.0);
  Body b = make_body(1.0, Vec3(1, 2, 3), q0, w);
  const double h = 1e-3;
  const long n = 1000000;
  const Body b0 = b;
  const long every = 1000;
  std::vector<Body> states;  // the student's steps as one call, every 1000th body kept
  rigid_spin_run(b, h, n, every, states);
  {
    INFO("the run returns " << n / every + 1 << " checkpoints, got " << states.size());
    REQUIRE(states.size() == std::size_t(n / every + 1));
  }
  require_body(states.front(), b0, 0.0, "the first checkpoint is the start");
  require_body(states.back(), b, 0.0, "the last checkpoint is the final body");
  for (std::size_t c = 0; c < states.size(); ++c) {  // the law at every checkpoint
    const double angle = double(c) * double(every) * h * w.norm();
    INFO("after " << c * std::size_t(every)
                  << " steps: q = " << states[c].q.coeffs().transpose());
    REQUIRE(wbtest::finite(orthonormality_error(rot(states[c]))) <= kOrthoTol);
    require_near(
        rot(states[c]),
        Mat3(Eigen::AngleAxisd(angle, w.normalized()).toRotationMatrix() * q0.toRotationMatrix()),
        kSameMotionTol, "R = rotation by n h |omega| about omega, times R_0");
  }
  // Every segment between two checkpoints is `every` steps of the header's update, taken here
  // from the first of them (never the lab's step continuing from a state it may have made up:
  // issue 42): the checkpoints are then the orbit of that update from b0 to rounding, whatever
  // code made them. The update: x += h v, q = dq q (dq the turn by |omega| h about omega), then
  // |q| = 1; the R4 held-out test holds the lab's step to it at 1e-14 per step.
  const double angle = w.norm() * h;
  const Vec3 axis = w.normalized() * std::sin(0.5 * angle);
  const Eigen::Quaterniond dq(std::cos(0.5 * angle), axis.x(), axis.y(), axis.z());
  for (std::size_t c = 0; c + 1 < states.size(); ++c) {
    Body r = states[c];
    for (long k = 0; k < every; ++k) {
      r.x += h * r.v;
      r.q = (dq * r.q).normalized();
    }
    INFO("the body after steps " << c * std::size_t(every) << " to "
                                 << (c + 1) * std::size_t(every)
                                 << ", stepped by the test itself from checkpoint " << c
                                 << ", must be the run's checkpoint " << c + 1
                                 << " (the run must take every step of the lab's update)");
    // 1000 steps of rounding (~1e-16 each) differ between the test's update and the lab's:
    // about 1e-13, a margin of 100.
    require_body(states[c + 1], r, 1e-11, "the checkpoint");
  }
  const Mat3 expected = Eigen::AngleAxisd(n * h * w.norm(), w.normalized()).toRotationMatrix() *
                        q0.toRotationMatrix();
  require_near(rot(b), expected, kSameMotionTol,
               "after 10^6 steps R = rotation by n h |omega| about omega, times R_0");
  INFO("after 10^6 steps q = " << b.q.coeffs().transpose() << ", expected finite");
  REQUIRE(b.q.coeffs().allFinite());
  const double err = orthonormality_error(rot(b));
  INFO("max(|R^T R - E|, |det R - 1|) after 10^6 steps = " << err << ", expected <= " << kOrthoTol
                                                           << " (renormalise q every step)");
  REQUIRE(wbtest::finite(err) <= kOrthoTol);
  INFO("|q| after 10^6 steps = " << b.q.norm());
  REQUIRE(std::abs(wbtest::finite(b.q.norm()) - 1.0) <= kOrthoTol);
}

TEST_CASE("R4 held-out: random spins turn q on the left by |omega| h and renormalise",
          "[rigid][R4][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("R4")) {
    INFO(g.replay());
    for (int s = 0; s < 6; ++s) {
      Body b0 = rigidtest::random_body(g);
      const double h = s == 2 ? g.uniform(1.0, 100.0) : g.log_uniform(1e-3, 0.2);
      if (s == 1) b0.omega.setZero();                                 // no axis: q stays
      if (s == 2) b0.omega = g.log_uniform(1e-11, 1e-9) * g.unit3();  // a very slow spin
      // q slightly off unit length (rounding builds up over a run): a turn renormalises it
      // (with omega = 0 the header lets q stay as it is: left unit there), however little it
      // is off (draw 3: 1e-12 to 1e-9, what a run's rounding leaves; a step that renormalises
      // only beyond a threshold lets |q| drift over a long run).
      if (s == 3)
        b0.q.coeffs() *= 1.0 + g.sign() * g.log_uniform(1e-12, 1e-9);
      else if (s != 1)
        b0.q.coeffs() *= 1.0 + g.uniform(-1e-3, 1e-3);
      Body b = b0, e = b0;
      e.x = b0.x + h * b0.v;
      const double a = b0.omega.norm() * h;
      if (a > 0) {
        const Vec3 axis = b0.omega / b0.omega.norm() * std::sin(0.5 * a);
        e.q = Eigen::Quaterniond(std::cos(0.5 * a), axis.x(), axis.y(), axis.z()) * b0.q;
      }
      if (a > 0) e.q.normalize();
      INFO("omega = " << rigidtest::str(b0.omega) << " (world), h = " << h << ", q = "
                      << b0.q.coeffs().transpose() << " (|q| = " << b0.q.norm() << ")");
      integrate_position(b, h);
      rigidtest::require_body(
          b, e, 1e-14,
          "x += h v; q = dq q (dq: angle |omega| h about omega, on the LEFT), "
          "then |q| = 1");
    }
  }
}

}  // namespace test_R4_integrate_position
