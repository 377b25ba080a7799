// Graded tests for TODO(R5), the velocity update with the gyroscopic term taken
// explicitly or implicitly (labs/rigid/integrate_velocity.cpp). Expected values:
// the update's definition, the exact energy change of the explicit step, and
// Euler's equations in closed form (a symmetric top's precession, the stability
// of rotation about the principal axes).
#include <cmath>
#include <vector>

#include "integrate_velocity.h"
#include "rigid_test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_R5_integrate_velocity {

using namespace rigidtest;

namespace {

// One update: a few 3x3 products and one 3x3 solve of entries ~1-10.
constexpr double kStepTol = 1e-12;
// L drift of semi-implicit Euler over 10 s of the tumbling body: O(h); the
// constant is a generous bound (the body turns ~20 rad in that time).
constexpr double kLDriftPerH = 10.0;
// Phase error of a first-order method after Omega T = 5 rad with h = 1e-4:
// ~ h Omega^2 T = 2.5e-3 rad; a 4x margin.
constexpr double kPrecessionTol = 1e-2;

struct Variant {
  const char* name;
  VelocityStep step;
};
const std::vector<Variant> kVariants = {{"explicit", integrate_velocity_explicit},
                                        {"implicit", integrate_velocity_implicit}};

// A tumbling body with three different moments (kg m^2), turned and spinning.
Body tumbling() {
  return make_body(2.0, Vec3(1.0, 2.0, 3.0), quat(0.7, 0.1, -0.4, 0.3), Vec3(1.0, -0.5, 2.0));
}

}  // namespace

TEST_CASE("R5 from rest: v = h f / m and omega = h I^-1 tau for both variants",
          "[rigid][R5][3pts]") {
  for (const Variant& var : kVariants) {
    INFO(var.name << " gyroscopic term");
    Body b = make_body(2.0, Vec3(1.0, 2.0, 3.0), quat(0.7, 0.1, -0.4, 0.3), Vec3::Zero(),
                       Vec3(1, 2, 3), Vec3(0.5, 0.0, -1.0));
    b.f = Vec3(4.0, -2.0, 1.0);
    b.tau = Vec3(0.5, 1.5, -2.0);
    const double h = 0.1;
    const Vec3 v0 = b.v;
    var.step(b, h);
    require_near(b.v, Vec3(v0 + h / b.m * Vec3(4.0, -2.0, 1.0)), kStepTol, "v = v0 + h f / m");
    require_near(b.omega, Vec3(h * inverse_inertia(b) * Vec3(0.5, 1.5, -2.0)), kStepTol,
                 "omega = h I^-1 tau (world I^-1 = R I_body^-1 R^T) when omega0 = 0");
    require_near(b.x, Vec3(1, 2, 3), 0.0, "x is not moved by the velocity update");
    // The accumulators are inputs: the caller clears them (integrate_velocity.h).
    require_near(b.f, Vec3(4.0, -2.0, 1.0), 0.0, "f is left as it was (not cleared or changed)");
    require_near(b.tau, Vec3(0.5, 1.5, -2.0), 0.0,
                 "tau is left as it was (not cleared or changed)");
    INFO("q " << b.q.coeffs().transpose() << ": the velocity update does not turn the body");
    REQUIRE(b.q.coeffs() == quat(0.7, 0.1, -0.4, 0.3).coeffs());
  }
}

TEST_CASE("R5 explicit one step: omega + h I^-1 (tau - omega x I omega)", "[rigid][R5][2pts]") {
  Body b = tumbling();
  b.tau = Vec3(0.3, -0.2, 0.1);
  const double h = 0.05;
  const Vec3 w = b.omega;
  const Vec3 expected = w + h * inverse_inertia(b) * (b.tau - w.cross(inertia(b) * w));
  integrate_velocity_explicit(b, h);
  require_near(b.omega, expected, kStepTol,
               "explicit: omega1 = omega0 + h I^-1 (tau - omega0 x (I omega0)), world frame");
}

TEST_CASE("R5 implicit one step: one Newton step on the body-frame gyroscopic equation",
          "[rigid][R5][2pts]") {
  Body b = tumbling();
  b.tau = Vec3(0.3, -0.2, 0.1);
  const double h = 0.05;
  const Mat3 R = rot(b), Ib = b.I_body;
  const Vec3 w = R.transpose() * b.omega;
  const Mat3 J = Ib + h * (rigid::skew(w) * Ib - rigid::skew(Ib * w));
  const Vec3 w1 = w - J.inverse() * (h * w.cross(Ib * w));
  const Vec3 expected = R * w1 + h * inverse_inertia(b) * b.tau;
  integrate_velocity_implicit(b, h);
  require_near(b.omega, expected, kStepTol,
               "implicit: w' = w - J^-1 (h w x I_body w), J = I_body + h ([w]x I_body - "
               "[I_body w]x), omega1 = R w' + h I^-1 tau");
}

TEST_CASE(
    "R5 torque-free: the explicit step gains exactly h^2/2 g.I^-1 g per step and the "
    "implicit one gains nothing",
    "[rigid][R5][4pts]") {
  // Explicit: omega1 = omega - h I^-1 g with g = omega x I omega, and omega.g = 0, so
  //   E1 - E0 = omega.I d + 1/2 d.I d = h^2/2 g.I^-1 g > 0      (d = omega1 - omega)
  // and turning the body about omega1 does not change E. Implicit: no gain.
  const double h = 0.01;
  Body b = tumbling();
  const double E0 = spin_energy(b);
  for (int k = 0; k < 2000; ++k) {
    const Vec3 g = b.omega.cross(inertia(b) * b.omega);
    const double gain = 0.5 * h * h * g.dot(inverse_inertia(b) * g);
    const double E = spin_energy(b);
    free_step(b, h, integrate_velocity_explicit);
    INFO("explicit step " << k);
    require_near(spin_energy(b) - E, gain, 1e-12 * E,
                 "explicit gyroscopic term: energy gain per step = h^2/2 (w x Iw).I^-1 (w x Iw)");
  }
  INFO("explicit: E0 = " << E0 << ", after 2000 steps E = " << spin_energy(b));
  REQUIRE(wbtest::finite(spin_energy(b)) > E0 * (1 + 1e-3));

  // Implicit: never a gain, over 2000 s (it loses some instead: the body drifts
  // towards its major axis), yet the body still spins after the first 20 s.
  Body c = tumbling();
  for (int k = 0; k < 200000; ++k) {
    const double E = spin_energy(c);
    free_step(c, h, integrate_velocity_implicit);
    if (!(spin_energy(c) <= E * (1 + 1e-13))) {
      INFO("implicit step " << k << ": E before " << E << ", after " << spin_energy(c));
      REQUIRE(wbtest::finite(spin_energy(c)) <= wbtest::finite(E) * (1 + 1e-13));
    }
    if (k == 1999) {
      INFO("implicit: E0 = " << E0 << ", after 20 s E = " << spin_energy(c));
      REQUIRE(wbtest::finite(spin_energy(c)) > 0.5 * E0);
    }
  }
  // The same on a thin rod (inertia ratio 1:10^4) tumbling while it spins: the
  // explicit step gains at every step, the implicit one never does.
  Body rod_e =
      make_body(1.0, Vec3(1.0, 1.0, 1e-4), quat(0.9, 0.2, 0.3, 0.1), Vec3(3.0, 0.5, 20.0));
  Body rod_i = rod_e;
  const double rod_E0 = spin_energy(rod_e);
  for (int k = 0; k < 10000; ++k) {
    const double Ee = spin_energy(rod_e), Ei = spin_energy(rod_i);
    free_step(rod_e, 1e-3, integrate_velocity_explicit);
    free_step(rod_i, 1e-3, integrate_velocity_implicit);
    if (!(spin_energy(rod_e) >= Ee * (1 - 1e-13) && spin_energy(rod_i) <= Ei * (1 + 1e-13))) {
      INFO("thin rod, step " << k << ": explicit E " << Ee << " -> " << spin_energy(rod_e)
                             << ", implicit E " << Ei << " -> " << spin_energy(rod_i));
      REQUIRE(wbtest::finite(spin_energy(rod_e)) >= wbtest::finite(Ee) * (1 - 1e-13));
      REQUIRE(wbtest::finite(spin_energy(rod_i)) <= wbtest::finite(Ei) * (1 + 1e-13));
    }
  }
  INFO("thin rod: E0 = " << rod_E0 << ", explicit after 10 s " << spin_energy(rod_e));
  REQUIRE(wbtest::finite(spin_energy(rod_e)) > rod_E0 * (1 + 1e-3));
}

TEST_CASE("R5 torque-free: angular momentum stays fixed in the world to first order in h",
          "[rigid][R5][3pts]") {
  // L = I omega is constant for a free body. Semi-implicit Euler keeps it to O(h)
  // over a fixed time: the error bound below, and halving h halves the drift.
  const double T = 10.0;
  for (const Variant& var : kVariants) {
    INFO(var.name << " gyroscopic term");
    double drift[2];
    for (int i = 0; i < 2; ++i) {
      const double h = i == 0 ? 1e-3 : 5e-4;
      Body b = tumbling();
      const Vec3 L0 = spin_momentum(b);
      double worst = 0;
      for (long k = 0; k < long(std::lround(T / h)); ++k) {
        free_step(b, h, var.step);
        worst = wbtest::worst_of(worst, (spin_momentum(b) - L0).norm() / L0.norm());
      }
      drift[i] = worst;
      INFO("h = " << h << ": max |L - L0| / |L0| over 10 s = " << worst);
      REQUIRE(wbtest::finite(worst) <= kLDriftPerH * h);
    }
    INFO("drift at h = 1e-3: " << drift[0] << ", at h = 5e-4: " << drift[1]
                               << ", expected a ratio near 2 (first order)");
    REQUIRE(wbtest::finite(drift[0] / drift[1]) >= 1.6);
    REQUIRE(wbtest::finite(drift[0] / drift[1]) <= 2.5);
  }
}

TEST_CASE("R5 symmetric top: omega in the body frame precesses at (I3 - I1) / I1 omega3",
          "[rigid][R5][3pts]") {
  // Euler's equations with I1 = I2: omega3 is constant and (omega1, omega2) turns
  // at Omega = (I3 - I1) / I1 omega3 (counterclockwise about body z).
  const double I1 = 1.0, I3 = 2.0, w3 = 5.0, Omega = (I3 - I1) / I1 * w3;
  const double h = 1e-4, T = 1.0;
  for (const Variant& var : kVariants) {
    INFO(var.name << " gyroscopic term");
    const Eigen::Quaterniond q0 = quat(0.9, 0.3, -0.2, 0.1);
    Body b = make_body(1.0, Vec3(I1, I1, I3), q0, q0.toRotationMatrix() * Vec3(0.3, 0.0, w3));
    for (long k = 0; k < long(std::lround(T / h)); ++k) free_step(b, h, var.step);
    const Vec3 wb = body_omega(b);
    const double angle = std::atan2(wb.y(), wb.x());
    const double expected = std::remainder(Omega * T, 2 * M_PI);
    require_near(std::remainder(angle - expected, 2 * M_PI), 0.0, kPrecessionTol,
                 "angle of (omega1, omega2) after 1 s = Omega T (mod 2 pi), Omega = 5 rad/s");
    require_near(wb.z(), w3, kPrecessionTol * w3, "omega3 stays constant");
    require_near(std::hypot(wb.x(), wb.y()), 0.3, kPrecessionTol * 0.3,
                 "|(omega1, omega2)| stays constant");
  }
}

TEST_CASE(
    "R5 principal axes: spin about the major and minor axes is stable and about the "
    "intermediate axis it flips",
    "[rigid][R5][3pts]") {
  // Linearising Euler's equations about a spin w about axis k: the perturbation
  // grows like exp(lambda t), lambda^2 = w^2 (I_k - I_i)(I_j - I_k) / (I_i I_j),
  // for the intermediate axis (lambda = 2 / sqrt(3) here: a factor ~1e5 in 10 s),
  // and oscillates with a bounded amplitude (ratio of the semi-axes below 2) about
  // the other two.
  const Vec3 I(1.0, 2.0, 3.0);
  const double w = 2.0, eps = 1e-3, h = 1e-3, T = 10.0;
  for (const Variant& var : kVariants) {
    for (int axis = 0; axis < 3; ++axis) {
      INFO(var.name << " gyroscopic term, spin about body axis " << axis);
      Vec3 wb = Vec3::Constant(eps);
      wb[axis] = w;
      const Eigen::Quaterniond q0 = quat(0.8, 0.4, 0.2, -0.4);
      Body b = make_body(1.0, I, q0, q0.toRotationMatrix() * wb);
      double max_perturbation = 0, min_spin = w;
      for (long k = 0; k < long(std::lround(T / h)); ++k) {
        free_step(b, h, var.step);
        const Vec3 now = body_omega(b);
        Vec3 off = now;
        off[axis] = 0;
        max_perturbation = wbtest::worst_of(max_perturbation, off.norm());
        min_spin = wbtest::least_of(min_spin, now[axis]);
      }
      INFO("largest perturbation " << max_perturbation << " (started at " << eps * std::sqrt(2.0)
                                   << "), smallest spin component " << min_spin);
      if (axis == 1) {
        REQUIRE(wbtest::finite(max_perturbation) > 0.5 * w);  // grew by a factor > 500
        REQUIRE(wbtest::finite(min_spin) < -0.5 * w);         // the spin flipped
      } else {
        REQUIRE(wbtest::finite(max_perturbation) < 4.0 * eps);
        REQUIRE(wbtest::finite(min_spin) > 0.99 * w);
      }
    }
  }
}

TEST_CASE("R5 held-out: random bodies take the explicit and implicit steps of the header",
          "[rigid][R5][held-out][4pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("R5")) {
    INFO(g.replay());
    for (int s = 0; s < 5; ++s) {
      const Body b0 = rigidtest::random_body(g);
      const double h = g.log_uniform(1e-3, 0.1);
      const Mat3 R = rot(b0), Ib = b0.I_body;
      const Mat3 Iinv = R * Ib.diagonal().cwiseInverse().asDiagonal() * R.transpose();
      const Mat3 Iw = R * Ib * R.transpose();
      Body e = b0;
      e.v = b0.v + h * b0.f / b0.m;
      e.omega = b0.omega + h * Iinv * (b0.tau - b0.omega.cross(Iw * b0.omega));
      INFO("m = " << b0.m << ", I_body diagonal " << Ib.diagonal().transpose()
                  << ", q = " << b0.q.coeffs().transpose() << ", v = " << rigidtest::str(b0.v)
                  << ", omega = " << rigidtest::str(b0.omega) << ", f = " << rigidtest::str(b0.f)
                  << ", tau = " << rigidtest::str(b0.tau) << ", h = " << h);
      Body b = b0;
      integrate_velocity_explicit(b, h);
      rigidtest::require_body(b, e, 1e-12,
                              "explicit: v += h f / m, omega += h I^-1 (tau - omega x I omega)");
      const Vec3 w = R.transpose() * b0.omega;
      const Mat3 J = Ib + h * (rigid::skew(w) * Ib - rigid::skew(Ib * w));
      const Vec3 w1 = w - J.inverse() * (h * w.cross(Ib * w));
      e.omega = R * w1 + h * Iinv * b0.tau;
      b = b0;
      integrate_velocity_implicit(b, h);
      rigidtest::require_body(b, e, 1e-12,
                              "implicit: one Newton step in the body frame, w' = w - J^-1 (h w x "
                              "I_body w), omega = R w' + h I^-1 tau");
    }
  }
}

}  // namespace test_R5_integrate_velocity
