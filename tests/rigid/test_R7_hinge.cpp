// Graded tests for TODO(R7), the point (ball) joint and the revolute hinge
// (labs/rigid/hinge.cpp). Expected values: the pinned point's velocity after the
// impulse, angular momentum about the pin (along the axis, for the revolute), the
// physical pendulum's period 2 pi sqrt(I / (m g d)) with I about the pin or the
// axis, and the Baumgarte bound on the drift.
#include <cmath>

#include "hinge.h"
#include "rigid_test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_R7_hinge {

using namespace rigidtest;

namespace {

constexpr double kImpulseTol = 1e-12;  // one 3x3 solve of entries ~1-10

Vec3 point_velocity(const Body& b, const Vec3& p) { return b.v + b.omega.cross(p - b.x); }

// A rod 1 m long (0.1 m square section), 1 kg, hanging from its top end.
struct Pendulum {
  Body b;
  Vec3 r_body = Vec3(0, 0, 0.5);  // the top end, body frame
  Vec3 anchor = Vec3::Zero();
  double d = 0.5;                         // pin to centre (m)
  double I_cm = 1.0 / 12 * (0.01 + 1.0);  // about a transverse axis (kg m^2)
  explicit Pendulum(double angle) {
    const Vec3 I(I_cm, I_cm, 1.0 / 12 * 0.02);
    const Eigen::Quaterniond q(Eigen::AngleAxisd(angle, Vec3::UnitY()));
    b = make_body(1.0, I, q, Vec3::Zero());
    b.x = anchor - q.toRotationMatrix() * r_body;  // the top end at the anchor
  }
  // Gravity, the (torque-free) velocity update, the hinge, the positions.
  void step(double h, double beta) {
    b.v += h * Vec3(0, 0, -9.81);
    b.omega -= h * inverse_inertia(b) * b.omega.cross(inertia(b) * b.omega);
    apply_hinge(b, r_body, anchor, h, beta);
    ref_position(b, h);
  }
  double drift() const { return (b.x + rot(b) * r_body - anchor).norm(); }
};

}  // namespace

TEST_CASE("R7 one impulse with beta 0: the pinned point stops and the impulse acts at it",
          "[rigid][R7][2pts]") {
  Body b = make_body(2.0, Vec3(0.5, 1.0, 1.25), quat(0.8, 0.3, -0.2, 0.4), Vec3(1.0, -2.0, 0.5),
                     Vec3(0.3, 0.1, -0.2), Vec3(1.5, -0.5, 2.0));
  const Vec3 r_body(0.4, -0.3, 0.6);
  const Vec3 anchor = b.x + rot(b) * r_body;  // pinned where it is
  const Vec3 L0 = momentum_about(b, anchor), mv0 = b.m * b.v;
  const Vec3 P = apply_hinge(b, r_body, anchor, 0.01, 0.0);
  require_near(point_velocity(b, anchor), Vec3::Zero(), kImpulseTol,
               "v + omega x r = 0 at the pin after the impulse");
  require_near(momentum_about(b, anchor), L0, kImpulseTol,
               "an impulse at the pin keeps the angular momentum about the pin");
  require_near(P, Vec3(b.m * b.v - mv0), kImpulseTol, "the returned P is the change of m v");
}

TEST_CASE("R7 hinged pendulum: small swings have period 2 pi sqrt(I_p / (m g d))",
          "[rigid][R7][1pts]") {
  // I_p = I_cm + m d^2 (parallel axis). At 0.05 rad the amplitude lengthens the
  // period by theta0^2 / 16 = 1.6e-4; semi-implicit Euler at h = 1e-3 shifts it
  // by O((h w)^2) ~ 1e-6. Zero crossings are interpolated to ~h^2.
  constexpr double kPeriodTol = 2e-3;  // relative
  Pendulum p(0.05);
  const double T0 = 2 * M_PI * std::sqrt((p.I_cm + p.d * p.d) / (9.81 * p.d));
  const double h = 1e-3;
  std::vector<double> crossings;  // downward crossings of x = 0 (cm moving to -x)
  double x_prev = p.b.x.x();
  for (int k = 1; k <= 8000 && crossings.size() < 4; ++k) {
    p.step(h, 0.2);
    const double x = p.b.x.x();
    if (x_prev > 0 && x <= 0) crossings.push_back(h * (k - 1 + x_prev / (x_prev - x)));
    x_prev = x;
  }
  INFO("the pendulum's centre crossed below the hinge moving to -x "
       << crossings.size() << " times in 8 s, expected 4 (about 5 periods of " << T0
       << " s): a body that never swings is held still (a hinge impulse that also stops the "
          "swing?) or never feels gravity");
  REQUIRE(crossings.size() == 4);
  const double T = (crossings.back() - crossings.front()) / 3.0;
  require_near(T, T0, 0.0, "period of the hinged rod (1 m, pinned at an end)", kPeriodTol);
}

TEST_CASE("R7 drift correction: beta/h of the drift is removed and a long run stays pinned",
          "[rigid][R7][2pts]") {
  // One impulse sets the pinned point's velocity to -(beta/h) C.
  {
    Body b = make_body(1.0, Vec3(1.0, 2.0, 3.0), quat(0.9, 0.1, 0.2, 0.3), Vec3(0.2, 0.1, -0.3),
                       Vec3::Zero(), Vec3(0.1, 0.0, 0.0));
    const Vec3 r_body(0.0, 0.0, 0.5);
    const Vec3 C(0.01, -0.02, 0.005);
    const Vec3 anchor = b.x + rot(b) * r_body - C;
    const double h = 0.01, beta = 0.3;
    apply_hinge(b, r_body, anchor, h, beta);
    require_near(point_velocity(b, anchor + C), Vec3(-beta / h * C), kImpulseTol,
                 "velocity of the pinned point after the impulse = -(beta / h) C");
  }
  // A large swing (from horizontal) for 100 s: each step leaves ~h^2 w^2 d of new
  // drift and removes the fraction beta, so it stays below ~h^2 w^2 d / beta
  // (w^2 <= 2 m g d / I_p ~ 30 /s^2 here): 8e-5 m; a 4x margin.
  const double h = 1e-3, beta = 0.2;
  Pendulum p(M_PI / 2);
  double worst = 0;
  for (int k = 0; k < 100000; ++k) {
    p.step(h, beta);
    worst = wbtest::worst_of(worst, p.drift());
  }
  INFO("largest drift of the pin over 100 s: " << worst << " m");
  REQUIRE(wbtest::finite(worst) <= 4 * h * h * 30.0 * 0.5 / beta);
  REQUIRE(wbtest::finite(p.b.x.norm()) <= 0.5 + 1e-3);  // still hanging from the pin
}

namespace {

// The revolute hinge's angular drift a x u (u = R axis_body), and a body's point
// velocity.
Vec3 axis_of(const Body& b, const Vec3& axis_body) { return rot(b) * axis_body; }

// A plate (0.3 x 0.05 x 1 m, 1 kg) hanging from a revolute hinge along `axis`
// through its top edge, its centre d = 0.5 m below, turned by `angle` about the axis.
struct Plate {
  Body b;
  Vec3 r_body = Vec3(0, 0, 0.5), anchor = Vec3::Zero(), axis, axis_body;
  Plate(const Vec3& a, double angle, const Vec3& omega) : axis(a.normalized()) {
    const Vec3 I(1.0 / 12 * (0.0025 + 1.0), 1.0 / 12 * (0.09 + 1.0), 1.0 / 12 * (0.09 + 0.0025));
    // Body x along the axis' horizontal part; turned about the axis by `angle`.
    const Eigen::Quaterniond q0 = rotation_from_to(Vec3::UnitY(), axis);
    const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)) * q0;
    b = make_body(1.0, I, q, omega);
    b.x = anchor - q.toRotationMatrix() * r_body;
    b.v = omega.cross(b.x - anchor);
    axis_body = rot(b).transpose() * axis;
  }
  void step(double h, double beta) {
    b.v += h * Vec3(0, 0, -9.81);
    b.omega -= h * inverse_inertia(b) * b.omega.cross(inertia(b) * b.omega);
    apply_revolute(b, r_body, anchor, axis_body, axis, h, beta);
    ref_position(b, h);
  }
  double angle_error() const {
    const Vec3 u = axis_of(b, axis_body);
    return std::atan2(u.cross(axis).norm(), u.dot(axis));
  }
  double drift() const { return (b.x + rot(b) * r_body - anchor).norm(); }
};

}  // namespace

TEST_CASE("R7 revolute with beta 0: the pin stops and omega turns to the axis in both rows",
          "[rigid][R7][2pts]") {
  // A body with omega off the axis in BOTH directions perpendicular to it (whatever
  // basis b1, b2 is used), pinned where it is with its axis along the hinge.
  Body b = make_body(2.0, Vec3(0.5, 1.0, 1.25), quat(0.8, 0.3, -0.2, 0.4), Vec3(1.0, -2.0, 0.5),
                     Vec3(0.3, 0.1, -0.2), Vec3(1.5, -0.5, 2.0));
  const Vec3 r_body(0.4, -0.3, 0.6);
  const Vec3 anchor = b.x + rot(b) * r_body;
  const Vec3 a = Vec3(0.2, 0.9, -0.4).normalized();
  const Vec3 axis_body = rot(b).transpose() * a;
  const Vec3 mv0 = b.m * b.v, Iw0 = inertia(b) * b.omega;
  const double La0 = momentum_about(b, anchor).dot(a);
  const RevoluteImpulse J = apply_revolute(b, r_body, anchor, axis_body, a, 0.01, 0.0);
  require_near(point_velocity(b, anchor), Vec3::Zero(), kImpulseTol,
               "the pinned point's velocity v + omega x r = 0 after the impulse");
  require_near(Vec3(b.omega - b.omega.dot(a) * a), Vec3::Zero(), kImpulseTol,
               "omega along the axis only: both angular rows (b1 and b2) hold");
  require_near(momentum_about(b, anchor).dot(a), La0, kImpulseTol,
               "angular momentum about the hinge axis is kept (the hinge never brakes it)");
  require_near(J.P, Vec3(b.m * b.v - mv0), kImpulseTol, "the returned P is the change of m v");
  const Vec3 r = anchor - b.x;
  require_near(J.M, Vec3(inertia(b) * b.omega - Iw0 - r.cross(J.P)), kImpulseTol,
               "the returned M: the change of I omega is r x P + M");
  require_near(J.M.dot(a), 0.0, kImpulseTol, "M is perpendicular to the axis");
}

TEST_CASE("R7 revolute drift: both the point and the axis drifts are corrected by beta / h",
          "[rigid][R7][2pts]") {
  // The point is off its anchor by C and the body's axis off the hinge axis by a small
  // turn: after one impulse the point moves at -(beta/h) C and the part of omega
  // across the axis is -(beta/h) (a x u).
  Body b = make_body(1.0, Vec3(1.0, 2.0, 3.0), quat(0.9, 0.1, 0.2, 0.3), Vec3(0.2, 0.1, -0.3),
                     Vec3::Zero(), Vec3(0.1, 0.0, 0.0));
  const Vec3 r_body(0.0, 0.0, 0.5);
  const Vec3 C(0.01, -0.02, 0.005);
  const Vec3 anchor = b.x + rot(b) * r_body - C;
  const Vec3 a = Vec3(1, 1, 1).normalized();
  const Vec3 axis_body =
      rot(b).transpose() * (Eigen::AngleAxisd(0.02, Vec3(1, -1, 0).normalized()) * a);
  const Vec3 u = rot(b) * axis_body;
  const double h = 0.01, beta = 0.3;
  apply_revolute(b, r_body, anchor, axis_body, a, h, beta);
  require_near(point_velocity(b, anchor + C), Vec3(-beta / h * C), kImpulseTol,
               "velocity of the pinned point after the impulse = -(beta / h) C");
  require_near(Vec3(b.omega - b.omega.dot(a) * a), Vec3(-beta / h * a.cross(u)), kImpulseTol,
               "omega across the axis = -(beta / h) (a x u): the axis turns back to a");
}

TEST_CASE("R7 revolute pendulum: period 2 pi sqrt(I_a / (m g d)) and the axis stays put",
          "[rigid][R7][2pts]") {
  // A plate on a tilted horizontal axis, released at 0.05 rad with a kick across the
  // axis (which the hinge removes): it swings about the axis only, with I_a its
  // inertia about the axis (parallel axis: I_c about the axis through the centre +
  // m d^2). Amplitude lengthens the period by theta0^2 / 16 ~ 1.6e-4, semi-implicit
  // Euler at h = 1e-3 by ~1e-6; zero crossings are interpolated to ~h^2.
  constexpr double kPeriodTol = 2e-3;  // relative
  constexpr double kAngleTol = 1e-3;   // rad: the axis' error after the first step
  constexpr double kAnchorTol = 1e-4;  // m
  const Vec3 a(std::cos(0.4), std::sin(0.4), 0.0);
  Plate p(a, 0.05, Vec3(0.3, -0.2, 0.5));
  const double Ic = p.axis_body.dot(p.b.I_body * p.axis_body);
  const double T0 = 2 * M_PI * std::sqrt((Ic + 0.25) / (9.81 * 0.5));
  const double h = 1e-3;
  const Vec3 across = a.cross(Vec3::UnitZ());  // horizontal, across the axis
  std::vector<double> crossings;
  double worst_angle = 0, worst_drift = 0;
  double s_prev = p.b.x.dot(across);
  for (int k = 1; k <= 10000; ++k) {
    p.step(h, 0.2);
    worst_angle = wbtest::worst_of(worst_angle, p.angle_error());
    worst_drift = wbtest::worst_of(worst_drift, p.drift());
    const double s = p.b.x.dot(across);
    if (s_prev > 0 && s <= 0) crossings.push_back(h * (k - 1 + s_prev / (s_prev - s)));
    s_prev = s;
  }
  INFO("largest angle between the body's axis and the hinge axis "
       << worst_angle << " rad, largest drift of the pin " << worst_drift << " m over 10 s");
  REQUIRE(wbtest::finite(worst_angle) <= kAngleTol);
  REQUIRE(wbtest::finite(worst_drift) <= kAnchorTol);
  REQUIRE(crossings.size() >= 4);  // nanfree: integers
  const double T = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  require_near(T, T0, 0.0, "period about the hinge axis, I_a = I_c + m d^2", kPeriodTol);
}

TEST_CASE("R7 held-out: random bodies pinned at random points take the header's impulses",
          "[rigid][R7][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("R7")) {
    INFO(g.replay());
    for (int s = 0; s < 4; ++s) {
      const Body b0 = rigidtest::random_body(g);
      const Vec3 r_body = g.vec3(-1, 1), axis_body = g.unit3();
      const double h = g.log_uniform(1e-3, 0.05), beta = g.uniform(0.0, 1.0);
      const Mat3 R = rot(b0);
      const Mat3 Iinv = R * b0.I_body.diagonal().cwiseInverse().asDiagonal() * R.transpose();
      const Vec3 r = R * r_body;
      const Vec3 anchor = b0.x + r + g.vec3(-0.05, 0.05);  // drifted a little
      const Vec3 C = b0.x + r - anchor;
      const Mat3 K = Mat3::Identity() / b0.m - rigid::skew(r) * Iinv * rigid::skew(r);
      INFO("body m = " << b0.m << ", v = " << rigidtest::str(b0.v)
                       << ", omega = " << rigidtest::str(b0.omega)
                       << "; r_body = " << rigidtest::str(r_body) << ", anchor "
                       << rigidtest::str(anchor) << ", h = " << h << ", beta = " << beta);
      // The point joint.
      const Vec3 P = K.ldlt().solve(-(b0.v + b0.omega.cross(r) + beta / h * C));
      Body e = b0;
      e.v += P / b0.m;
      e.omega += Iinv * r.cross(P);
      Body b = b0;
      const Vec3 Pg = apply_hinge(b, r_body, anchor, h, beta);
      rigidtest::require_near(Pg, P, 1e-10,
                              "apply_hinge: P from K P = -(v + omega x r + beta/h C)", 1e-10);
      rigidtest::require_body(b, e, 1e-10, "apply_hinge: v += P / m, omega += I^-1 (r x P)");
      // The revolute hinge: its axis a near the body's axis.
      const Vec3 u = R * axis_body;
      const Vec3 a = (u + g.vec3(-0.05, 0.05)).normalized();
      Vec3 b1, b2;
      rigid::tangent_basis(a, b1, b2);
      Eigen::Matrix<double, 3, 2> B;
      B << b1, b2;
      const Eigen::Vector2d Ca = B.transpose() * a.cross(u);
      Eigen::Matrix<double, 5, 5> KK;
      KK.topLeftCorner<3, 3>() = K;
      KK.topRightCorner<3, 2>() = -rigid::skew(r) * Iinv * B;
      KK.bottomLeftCorner<2, 3>() = B.transpose() * Iinv * rigid::skew(r);
      KK.bottomRightCorner<2, 2>() = B.transpose() * Iinv * B;
      Eigen::Matrix<double, 5, 1> rhs;
      rhs << -(b0.v + b0.omega.cross(r)) - beta / h * C,
          -B.transpose() * b0.omega - beta / h * Ca;
      const Eigen::Matrix<double, 5, 1> lam = KK.ldlt().solve(rhs);
      const Vec3 P2 = lam.head<3>(), M2 = B * lam.tail<2>();
      e = b0;
      e.v += P2 / b0.m;
      e.omega += Iinv * (r.cross(P2) + M2);
      b = b0;
      const RevoluteImpulse ri = apply_revolute(b, r_body, anchor, axis_body, a, h, beta);
      INFO("revolute: axis " << rigidtest::str(a) << ", the body's axis " << rigidtest::str(u));
      rigidtest::require_near(ri.P, P2, 1e-9, "apply_revolute: P of the 5x5 system", 1e-9);
      rigidtest::require_near(ri.M, M2, 1e-9, "apply_revolute: M = B mu of the 5x5 system", 1e-9);
      rigidtest::require_body(b, e, 1e-9,
                              "apply_revolute: v += P / m, omega += I^-1 (r x P + M)");
    }
  }
}

}  // namespace test_R7_hinge
