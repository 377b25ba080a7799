// Graded tests for TODO(R4), the position and orientation update
// (labs/rigid/integrate_position.cpp). Expected values: rotations about a fixed
// axis compose by adding angles, and rotation matrices are orthonormal.
#include <cmath>
#include <string>
#include <vector>

#include "integrate_position.h"
#include "params.h"
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

// The scenarios of the public tests below, each a function of its parameters: the public test
// runs it with the published ones (wbtest::Params()), the held-out test with drawn ones in the
// same format (tests/common/params.h): short decimals within half of the published value either
// side (quaternion components within 0.2), the orientations from quaternions of short decimals.
// The mass and the moments, which the position update does not read, stay as published: the
// public calls' largest number is often the moment 3, and a drawn one would tell them apart.
// The held-out runs are shorter (the share of calls the public tests have, as tools/adversary
// --inputs samples them).
// A slow turn (omega h = 0.02 rad per step) or a fast spin (omega h = 1 rad per step), 1000 steps
// of 0.01 s; held-out: 25 of them from a drawn point of the same run (reached by the test's
// own update, rigidtest::ref_position), so that the states are the public run's, in its format
// and magnitudes.
void constant_omega(const wbtest::Params& p, double published_speed) {
  const double speed = p.num(published_speed, 0.5 * published_speed, 1.5 * published_speed);
  INFO("|omega| = " << speed << " rad/s");
  const Vec3 w = speed * num3(p, Vec3(0.4, -1.1, 2.0)).normalized(),
             v = num3(p, Vec3(1.0, -0.5, 2.0));
  Body b = make_body(1.5, Vec3(1, 2, 3), quat_near(p, 0.6, 0.2, -0.5, 0.3), w,
                     num3(p, Vec3(0.1, 0.2, 0.3)), v);
  const double h = p.num(0.01, 0.005, 0.015);
  const long skipped = p.count(0, 0, 975), n = p.steps(1000, 25);
  for (long k = 0; k < skipped; ++k) ref_position(b, h);
  const Eigen::Quaterniond q0 = b.q;
  const Vec3 x0 = b.x;
  INFO(n << " steps of h = " << h << " from the state after " << skipped
         << " steps: x = " << str(x0) << ", q = " << q0.coeffs().transpose());
  for (long k = 0; k < n; ++k) integrate_position(b, h);
  // Rotations about one fixed (world) axis add their angles; the world-frame omega
  // turns the body AFTER its current orientation: R_n = Rot(n h |w|, w) R_0.
  const Mat3 expected =
      Eigen::AngleAxisd(double(n) * h * w.norm(), w.normalized()).toRotationMatrix() *
      q0.toRotationMatrix();
  require_near(rot(b), expected, kComposeTol,
               "R after n steps = rotation by n h |omega| about omega (world frame), times R_0");
  require_near(b.x, Vec3(x0 + double(n) * h * v), kComposeTol, "x after n steps = x0 + n h v",
               kComposeTol);
  require_near(b.omega, w, 0.0, "omega is not changed by the position update");
}

// omega = 0 (one step), a tiny omega (1000 steps of 1 s; held-out 45 steps of 0.5 to 1.5 s: a
// turn of ~1e-8 rad, far above the comparison's 1e-11), a spin along the body's first axis
// (100 steps; held-out 4).
void zero_tiny_axis(const wbtest::Params& p) {
  const Eigen::Quaterniond q0 = quat_near(p, 0.9, 0.1, 0.3, -0.2);
  const Vec3 I(1, 2, 3), v = num3(p, Vec3(0.0, 3.0, 0.0));
  const double m = 1.0, h0 = p.num(0.5, 0.25, 0.75);
  Body b = make_body(m, I, q0, Vec3::Zero(), Vec3::Zero(), v);
  integrate_position(b, h0);
  INFO("omega = 0: q = " << b.q.coeffs().transpose()
                         << ", expected finite: the rotation by a zero angle is the identity "
                            "(do not divide by |omega| when it is 0)");
  REQUIRE(b.q.coeffs().allFinite());
  require_near(rot(b), q0.toRotationMatrix(), kComposeTol, "omega = 0: the orientation stays");
  require_near(b.x, Vec3(h0 * v), kComposeTol, "x = x0 + h v");
  // A tiny omega (1e-10 rad/s) is not zero: over 1000 steps of 1 s the body turns
  // by 1e-7 rad, which the comparison sees (a threshold on |omega| would not turn it).
  const Vec3 tiny(p.num(6e-11, 3e-11, 9e-11), 0.0, p.num(-8e-11, -1.2e-10, -4e-11));
  const double h1 = p.num(1.0, 0.5, 1.5);
  const long n1 = p.steps(1000, 45);
  Body t = make_body(m, I, q0, tiny);
  for (long k = 0; k < n1; ++k) integrate_position(t, h1);
  INFO("q after " << n1 << " steps of " << h1 << " s at omega = " << str(tiny)
                  << " rad/s: " << t.q.coeffs().transpose() << ", expected finite");
  REQUIRE(t.q.coeffs().allFinite());
  require_near(
      rot(t),
      Mat3(
          Eigen::AngleAxisd(double(n1) * h1 * tiny.norm(), tiny.normalized()).toRotationMatrix() *
          q0.toRotationMatrix()),
      kComposeTol,
      "omega ~ 1e-10 rad/s: turned by n h |omega| (only omega = 0 exactly means no turn)");
  // A spin exactly along the body's first axis: the axis does not move.
  Body s = make_body(m, I, q0, Vec3(p.num(5.0, 2.5, 7.5) * q0.toRotationMatrix().col(0)));
  const double h2 = p.num(0.01, 0.005, 0.015);
  for (long k = 0; k < p.steps(100, 4); ++k) integrate_position(s, h2);
  INFO("spin along a principal axis: q = " << s.q.coeffs().transpose() << ", expected finite");
  REQUIRE(s.q.coeffs().allFinite());
  require_near(Vec3(rot(s).col(0)), Vec3(q0.toRotationMatrix().col(0)), kComposeTol,
               "spinning about its own axis 0, the body's axis 0 stays where it was");
}

// A constant omega for 10^6 steps (held-out: 10^4, one call either way: its length is no
// input's property, and the held-out test's time stays small).
void long_run(const wbtest::Params& p) {
  // A constant omega: every step multiplies by the same dq, so whatever rounding
  // |dq| carries adds up steadily instead of averaging out (a changing omega
  // would hide a missing renormalisation).
  const Eigen::Quaterniond q0 = quat_near(p, 0.5, 0.5, -0.5, 0.5);
  const Vec3 w = num3(p, Vec3(3.0, -2.0, 5.0));
  Body b = make_body(1.0, Vec3(1, 2, 3), q0, w);
  const double h = p.num(1e-3, 5e-4, 1.5e-3);
  const long n = p.steps(1000000, 10000);
  const std::string run = p.held_out() ? "the held-out run" : "10^6 steps";
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
  const Mat3 expected =
      Eigen::AngleAxisd(double(n) * h * w.norm(), w.normalized()).toRotationMatrix() *
      q0.toRotationMatrix();
  require_near(rot(b), expected, kSameMotionTol,
               "after " + run + " R = rotation by n h |omega| about omega, times R_0");
  INFO("after " << run << " q = " << b.q.coeffs().transpose() << ", expected finite");
  REQUIRE(b.q.coeffs().allFinite());
  const double err = orthonormality_error(rot(b));
  INFO("max(|R^T R - E|, |det R - 1|) after "
       << run << " = " << err << ", expected <= " << kOrthoTol << " (renormalise q every step)");
  REQUIRE(wbtest::finite(err) <= kOrthoTol);
  INFO("|q| after " << run << " = " << b.q.norm());
  REQUIRE(std::abs(wbtest::finite(b.q.norm()) - 1.0) <= kOrthoTol);
}

}  // namespace

TEST_CASE("R4 constant omega: after n steps the body has turned by n h |omega| about omega",
          "[rigid][R4][3pts]") {
  for (double speed : {2.0, 100.0}) constant_omega(wbtest::Params(), speed);
}

TEST_CASE(
    "R4 omega zero or along a principal axis: no NaN from a zero angle and the centre moves",
    "[rigid][R4][3pts]") {
  zero_tiny_axis(wbtest::Params());
}

TEST_CASE("R4 R stays orthonormal with det R = 1 after a million steps", "[rigid][R4][4pts]") {
  long_run(wbtest::Params());
}

// The public scenarios again, their parameters drawn from the held-out seed in the public tests'
// format, in the share of calls they have there; then the header's update, one step at a time,
// on random bodies (short decimals too: rigidtest::random_body), among them the cases a mistake
// needs (omega = 0, a very slow spin, q off unit length by what a run's rounding leaves).
TEST_CASE("R4 held-out: random spins turn q on the left by |omega| h and renormalise",
          "[rigid][R4][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("R4")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    for (double speed : {2.0, 100.0}) constant_omega(p, speed);
    zero_tiny_axis(p);
    long_run(p);
    const auto d = [](double x) { return wbtest::Params::short_decimal(x); };
    for (int s = 0; s < 6; ++s) {
      Body b0 = rigidtest::random_body(g);
      const double h = d(s == 2 ? g.uniform(1.0, 100.0) : g.log_uniform(1e-3, 0.2));
      if (s == 1) b0.omega.setZero();  // no axis: q stays
      if (s == 2)                      // a very slow spin
        b0.omega = Vec3(d(g.signed_uniform(1e-11, 1e-9)), d(g.signed_uniform(1e-11, 1e-9)),
                        d(g.signed_uniform(1e-11, 1e-9)));
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
