// Graded tests for TODO(R7), the hinge impulse (labs/rigid/hinge.cpp). Expected
// values: the pinned point's velocity after the impulse, angular momentum about
// the pin, the physical pendulum's period 2 pi sqrt(I_p / (m g d)), and the
// Baumgarte bound on the drift.
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
          "[rigid][R7][5pts]") {
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
          "[rigid][R7][4pts]") {
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
          "[rigid][R7][4pts]") {
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
    worst = std::max(worst, p.drift());
  }
  INFO("largest drift of the pin over 100 s: " << worst << " m");
  REQUIRE(worst <= 4 * h * h * 30.0 * 0.5 / beta);
  REQUIRE(p.b.x.norm() <= 0.5 + 1e-3);  // still hanging from the pin
}

}  // namespace test_R7_hinge
