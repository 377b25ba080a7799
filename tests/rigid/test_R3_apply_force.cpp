// Graded tests for TODO(R3), forces and torques (labs/rigid/apply_force.cpp).
// Expected values: the definition of the moment of a force, tau = (p - x) x F,
// worked out by hand for lever arms along the axes.
#include "apply_force.h"
#include "rigid_test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_R3_apply_force {

using namespace rigidtest;

namespace {
// One cross product and a sum of numbers ~1-10: a few ulps.
constexpr double kTol = 1e-13;
}  // namespace

TEST_CASE("R3 a force through the centre of mass pushes and gives no torque",
          "[rigid][R3][3pts]") {
  Body b = make_body(2.0, Vec3(1, 2, 3), quat(1, 0.2, 0.3, 0), Vec3::Zero(), Vec3(1, -2, 0.5));
  const Vec3 F(3.0, -1.0, 2.0);
  apply_force(b, F, b.x + 2.5 * F);  // the point lies on the line of action through x
  require_near(b.f, F, kTol, "f = F");
  require_near(b.tau, Vec3::Zero(), kTol, "tau = (p - x) x F = 0 when p - x is parallel to F");
}

TEST_CASE("R3 a force at a lever arm adds the torque (p - x) x F to what is there",
          "[rigid][R3][2pts]") {
  Body b = make_body(2.0, Vec3(1, 2, 3), quat(1, 0, 0, 0), Vec3::Zero(), Vec3(1, 1, 1));
  b.f = Vec3(0.5, 0.0, -1.0);
  b.tau = Vec3(0.25, 1.0, 0.0);
  // Lever arm 2 m along x, force 3 N along z: tau = 2 e_x x 3 e_z = -6 e_y.
  apply_force(b, Vec3(0, 0, 3), b.x + Vec3(2, 0, 0));
  // Lever arm 1 m along y, force 4 N along x: tau = e_y x 4 e_x = -4 e_z.
  apply_force(b, Vec3(4, 0, 0), b.x + Vec3(0, 1, 0));
  require_near(b.f, Vec3(4.5, 0.0, 2.0), kTol,
               "f adds every force: (0.5, 0, -1) + 3 e_z + 4 e_x");
  require_near(b.tau, Vec3(0.25, -5.0, -4.0), kTol,
               "tau adds (p - x) x F: (0.25, 1, 0) - 6 e_y - 4 e_z (the lever arm first)");
  require_near(b.v, Vec3::Zero(), 0.0,
               "v unchanged: apply_force only accumulates f and tau, the step integrates them");
  require_near(b.x, Vec3(1, 1, 1), 0.0, "x unchanged by apply_force");
}

TEST_CASE("R3 gravity adds m g at the centre of mass and no torque", "[rigid][R3][2pts]") {
  Body b = make_body(2.5, Vec3(1, 2, 3), quat(0.3, 0.2, 0.9, 0), Vec3(1, 2, 3), Vec3(4, 5, 6));
  b.f = Vec3(1.0, 0.0, 0.0);
  b.tau = Vec3(0.0, 2.0, 0.0);
  apply_gravity(b, Vec3(0.0, -1.0, -9.81));
  require_near(b.f, Vec3(1.0, -2.5, -24.525), kTol, "f += m g with m = 2.5 kg");
  require_near(b.tau, Vec3(0.0, 2.0, 0.0), kTol, "gravity acts at the centre: tau unchanged");
  require_near(b.v, Vec3::Zero(), 0.0,
               "v unchanged: forces only accumulate in f, the step integrates them");
  require_near(b.x, Vec3(4, 5, 6), 0.0, "x unchanged by apply_gravity");
  require_near(b.omega, Vec3(1, 2, 3), 0.0, "omega unchanged by a force");
}

TEST_CASE("R3 held-out: random forces at random points add F and (p - x) x F and gravity m g",
          "[rigid][R3][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("R3")) {
    INFO(g.replay());
    for (int s = 0; s < 5; ++s) {
      const Body b0 = rigidtest::random_body(g);
      const Vec3 F = g.vec3(-10, 10), p = b0.x + g.vec3(-2, 2), grav = g.vec3(-10, 10);
      Body b = b0, e = b0;
      e.f += F;
      e.tau += (p - b0.x).cross(F);
      INFO("F = " << rigidtest::str(F) << " at p = " << rigidtest::str(p) << ", x = "
                  << rigidtest::str(b0.x) << ", f and tau already there: " << rigidtest::str(b0.f)
                  << ", " << rigidtest::str(b0.tau));
      apply_force(b, F, p);
      rigidtest::require_body(b, e, 1e-13,
                              "apply_force: f += F, tau += (p - x) x F, nothing else");
      e.f += b0.m * grav;
      apply_gravity(b, grav);
      INFO("g = " << rigidtest::str(grav) << ", m = " << b0.m);
      rigidtest::require_body(b, e, 1e-13, "apply_gravity: f += m g, no torque, nothing else");
    }
  }
}

}  // namespace test_R3_apply_force
