// Graded tests for C2, particle-particle response (labs/collisions/collide_particles.cpp).
// Expected values: conservation of momentum (the impulses are equal and
// opposite), the kinetic energy lost in a collision of restitution e,
//   dK = -(1 - e^2) / 2 * m1 m2 / (m1 + m2) * v_n^2,
// the lecture's elastic formula v1' = v1 - 2 m2 / (m1 + m2) ((v1 - v2).n) n, and
// the centre of mass left in place by the separation.
#include <cmath>

#include "collide_particles.h"
#include "heldout.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_C2_collide_particles {

namespace {

using wb::Vec2;
using wbtest::require_near;

constexpr double kRound = 1e-12;  // rounding of O(1) sums and a square root: the laws are exact

double kinetic(double m1, const Vec2& v1, double m2, const Vec2& v2) {
  return 0.5 * m1 * v1.squaredNorm() + 0.5 * m2 * v2.squaredNorm();
}

// An oblique contact: centres 0.35 apart along n = (0.28, 0.96), radii 0.2 + 0.2 (overlap 0.05).
const Vec2 kN(0.28, 0.96);
const Vec2 kX2(-0.4, 0.15);
const Vec2 kX1 = kX2 + 0.35 * kN;

}  // namespace

TEST_CASE("C2 collide_particles: equal masses head-on with e = 1 exchange normal velocities",
          "[collisions][C2][3pts]") {
  Vec2 x1(0.0, 0.0), x2(0.19, 0.0);  // radii 0.1: overlap 0.01 along x
  Vec2 v1(2.0, 0.3), v2(-1.0, -0.4);
  const double J = collide_particles(1.2, 0.1, 1.2, 0.1, 1.0, x1, v1, x2, v2);
  require_near(v1, Vec2(-1.0, 0.3), kRound,
               "particle 1 takes particle 2's normal velocity, keeps its tangential one");
  require_near(v2, Vec2(2.0, -0.4), kRound,
               "particle 2 takes particle 1's normal velocity, keeps its tangential one");
  require_near(J, 1.2 * 3.0, kRound, "J = m v_rel for equal masses and e = 1");
  require_near((x2 - x1).norm(), 0.2, kRound, "separated until they just touch (r1 + r2)");
}

TEST_CASE(
    "C2 collide_particles: momentum conserved to rounding and kinetic energy lost by "
    "(1 - e^2)/2 mu v_n^2",
    "[collisions][C2][3pts]") {
  const double m1 = 1.5, m2 = 4.0, mu = m1 * m2 / (m1 + m2);
  for (double e : {1.0, 0.6, 0.0}) {
    Vec2 x1 = kX1, x2 = kX2;
    Vec2 v1(0.7, -2.1), v2(-0.3, 0.8);
    const Vec2 p0 = m1 * v1 + m2 * v2;
    const double K0 = kinetic(m1, v1, m2, v2);
    const double vn = (v1 - v2).dot(kN);  // -2.504 < 0: approaching
    collide_particles(m1, 0.2, m2, 0.2, e, x1, v1, x2, v2);
    INFO("restitution " << e);
    require_near(Vec2(m1 * v1 + m2 * v2), p0, kRound,
                 "total momentum (equal, opposite impulses)");
    require_near(kinetic(m1, v1, m2, v2) - K0, -0.5 * (1 - e * e) * mu * vn * vn, kRound,
                 "kinetic energy change -(1 - e^2)/2 m1 m2/(m1 + m2) v_n^2");
    require_near((v1 - v2).dot(kN), -e * vn, kRound, "relative normal velocity after: -e v_n");
  }
}

TEST_CASE("C2 collide_particles: e = 1 reproduces the lecture's elastic velocity formula",
          "[collisions][C2][2pts]") {
  const double m1 = 1.5, m2 = 4.0;
  Vec2 x1 = kX1, x2 = kX2;
  Vec2 v1(0.7, -2.1), v2(-0.3, 0.8);
  const double vn = (v1 - v2).dot(kN);
  const Vec2 e1 = v1 - 2 * m2 / (m1 + m2) * vn * kN;
  const Vec2 e2 = v2 + 2 * m1 / (m1 + m2) * vn * kN;
  const double J = collide_particles(m1, 0.2, m2, 0.2, 1.0, x1, v1, x2, v2);
  require_near(v1, e1, kRound, "v1' = v1 - 2 m2/(m1 + m2) ((v1 - v2).n) n");
  require_near(v2, e2, kRound, "v2' = v2 + 2 m1/(m1 + m2) ((v1 - v2).n) n");
  require_near(J, -2 * vn * m1 * m2 / (m1 + m2), kRound, "J = -(1 + e) v_n / (1/m1 + 1/m2)");
}

TEST_CASE("C2 collide_particles: a 1 to 10^6 mass ratio behaves like a wall",
          "[collisions][C2][2pts]") {
  const double m1 = 1.0, m2 = 1e6, e = 0.5;
  Vec2 x1 = kX1, x2 = kX2;
  Vec2 v1 = -2.0 * kN + Vec2(0.96, -0.28), v2(0.0, 0.0);
  collide_particles(m1, 0.2, m2, 0.2, e, x1, v1, x2, v2);
  // The exact answer differs from a wall's by the factor m2/(m1 + m2) = 1 - 1e-6.
  constexpr double kWallTol = 1e-5;  // 1e-6 relative, times the speeds (<= 3 m/s)
  require_near(v1, Vec2(1.0 * kN + Vec2(0.96, -0.28)), kWallTol,
               "the light particle bounces as off a wall: normal speed -e v_n");
  require_near(v2, Vec2(-3.0 * 1e-6 * kN), 1e-11,
               "the heavy one takes -J/m2 n, J = (1 + e) 2 m1 m2 / (m1 + m2): 3e-6 m/s along -n");
  require_near(x1, Vec2(kX1 + 0.05 * kN), 1e-7, "the light one is moved out by nearly all 0.05");
  require_near(x2, Vec2(kX2 - 0.05e-6 * kN), 1e-12, "the heavy one moves by 0.05 m1/(m1 + m2)");
}

TEST_CASE(
    "C2 collide_particles: receding particles get no impulse but are separated without "
    "moving the centre of mass",
    "[collisions][C2][3pts]") {
  const double m1 = 2.0, m2 = 0.5;
  Vec2 x1 = kX1, x2 = kX2;
  const Vec2 v1_0 = 0.4 * kN + Vec2(0.1, 0.2), v2_0(-0.3, 0.05);  // (v1 - v2).n > 0
  Vec2 v1 = v1_0, v2 = v2_0;
  const Vec2 c0 = (m1 * x1 + m2 * x2) / (m1 + m2);
  const double J = collide_particles(m1, 0.2, m2, 0.2, 1.0, x1, v1, x2, v2);
  require_near(v1, v1_0, kRound, "particle 1 velocity: receding, no impulse");
  require_near(v2, v2_0, kRound, "particle 2 velocity: receding, no impulse");
  require_near(J, 0.0, 0.0, "returned impulse for receding particles");
  require_near((x1 - x2).norm(), 0.4, kRound, "separated to r1 + r2");
  require_near(Vec2((m1 * x1 + m2 * x2) / (m1 + m2)), c0, kRound,
               "centre of mass unchanged by the separation");
  require_near(x1, Vec2(kX1 + 0.01 * kN), kRound,
               "particle 1 moved by 0.05 (1/m1)/(1/m1 + 1/m2)");
}

TEST_CASE("C2 collide_particles: coincident centres use the fallback normal +y without NaN",
          "[collisions][C2][3pts]") {
  const Vec2 c(0.5, -0.3);
  Vec2 x1 = c, x2 = c;
  Vec2 v1(0.2, -1.0), v2(0.1, 1.0);  // (v1 - v2).(0, 1) = -2: approaching along the fallback
  const double J = collide_particles(1.0, 0.1, 3.0, 0.3, 0.5, x1, v1, x2, v2);
  wb::Mat2X after(2, 4);
  after << x1, x2, v1, v2;
  wbtest::require_finite(after, "positions and velocities after coincident centres");
  require_near(J, 2.25, kRound, "J = (1 + 0.5) 2 / (1 + 1/3)");
  require_near(v1, Vec2(0.2, 1.25), kRound, "v1 + (J/m1) (0, 1)");
  require_near(v2, Vec2(0.1, 0.25), kRound, "v2 - (J/m2) (0, 1)");
  require_near(x1, Vec2(0.5, 0.0), kRound,
               "x1 moved up by 0.4 (1/m1)/(1/m1 + 1/m2) = 0.3 along (0, 1)");
  require_near(x2, Vec2(0.5, -0.4), kRound, "x2 moved down by 0.4 (1/m2)/(1/m1 + 1/m2) = 0.1");
}

TEST_CASE("C2 collide_particles: discs apart get nothing and touching discs are in contact",
          "[collisions][C2][3pts]") {
  {
    // Unequal radii 0.1 and 0.3 (contact when dist <= r1 + r2 = 0.4), each side of it.
    Vec2 x1(0.0, 0.0), x2(0.41, 0.0), v1(1.0, 0.0), v2(-1.0, 0.0);
    double J = collide_particles(0.5, 0.1, 2.0, 0.3, 1.0, x1, v1, x2, v2);
    require_near(J, 0.0, 0.0, "impulse between discs of radii 0.1 and 0.3, 0.41 apart");
    require_near(x1, Vec2(0.0, 0.0), 0.0, "position of a disc not in contact (r1 + r2 = 0.4)");
    x2 = Vec2(0.39, 0.0);
    J = collide_particles(0.5, 0.1, 2.0, 0.3, 1.0, x1, v1, x2, v2);
    require_near(J, 2.0 * 2.0 / (1 / 0.5 + 1 / 2.0), kRound,
                 "discs of radii 0.1 and 0.3, 0.39 apart: in contact (s = r1 + r2 - dist > 0), "
                 "J = -(1 + e) v_n / (1/m1 + 1/m2)");
    require_near((x2 - x1).norm(), 0.4, kRound, "separated to r1 + r2 = 0.4");
  }
  {
    Vec2 x1(0.0, 0.0), x2(0.51, 0.0), v1(1.0, 0.0), v2(-1.0, 0.0);  // gap 0.01
    const double J = collide_particles(1.0, 0.25, 1.0, 0.25, 1.0, x1, v1, x2, v2);
    require_near(J, 0.0, 0.0, "impulse between discs 0.01 apart");
    require_near(v1, Vec2(1.0, 0.0), 0.0, "velocity of a disc not in contact");
    require_near(x2, Vec2(0.51, 0.0), 0.0, "position of a disc not in contact");
  }
  Vec2 x1(0.0, 0.0), x2(0.5, 0.0), v1(1.0, 0.0), v2(-1.0, 0.0);  // touching exactly
  const double J = collide_particles(1.0, 0.25, 1.0, 0.25, 1.0, x1, v1, x2, v2);
  require_near(J, 2.0, kRound,
               "touching and approaching: J = -(1 + e) v_n / (1/m1 + 1/m2) = 2 * 2 / 2");
  require_near(v1, Vec2(-1.0, 0.0), kRound, "touching discs exchange velocities (e = 1)");
}

TEST_CASE(
    "C2 collide_particles: approaching is decided by the relative normal velocity and not "
    "by one particle's",
    "[collisions][C2][2pts]") {
  // Particle 1 above particle 2 (n = +y), both falling: 1 at 1 m/s, 2 at 3 m/s.
  // v1.n < 0, but (v1 - v2).n = 2 > 0: they separate, no impulse.
  Vec2 x1(0.0, 0.35), x2(0.0, 0.0), v1(0.0, -1.0), v2(0.0, -3.0);
  double J = collide_particles(1.0, 0.2, 1.0, 0.2, 1.0, x1, v1, x2, v2);
  require_near(J, 0.0, 0.0, "impulse when (v1 - v2).n = +2 (receding) although v1.n < 0");
  require_near(v1, Vec2(0.0, -1.0), 0.0, "velocity of particle 1: receding, unchanged");
  require_near(v2, Vec2(0.0, -3.0), 0.0, "velocity of particle 2: receding, unchanged");
  // Swapped speeds: v1.n and v2.n both < 0, but particle 1 catches up, v_n = -2.
  x1 = Vec2(0.0, 0.35);
  x2 = Vec2(0.0, 0.0);
  v1 = Vec2(0.0, -3.0);
  v2 = Vec2(0.0, -1.0);
  J = collide_particles(1.0, 0.2, 1.0, 0.2, 1.0, x1, v1, x2, v2);
  require_near(J, 2.0, kRound, "(v1 - v2).n = -2: approaching, J = -(1 + 1) (-2) / 2");
  require_near(v1, Vec2(0.0, -1.0), kRound, "equal masses, e = 1: velocities exchanged");
}

TEST_CASE("C2 held-out: random pairs of discs in and out of contact follow the header",
          "[collisions][C2][held-out][4pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("C2")) {
    INFO(g.replay());
    // The header's response, written here, against the lab's.
    auto check = [](double m1, double r1, double m2, double r2, double e, const Vec2& x1,
                    const Vec2& x2, const Vec2& v1, const Vec2& v2) {
      const double dist = (x1 - x2).norm(), sgap = r1 + r2 - dist;
      const Vec2 n = dist > 0 ? Vec2((x1 - x2) / dist) : Vec2(0, 1);
      const double vn = (v1 - v2).dot(n), w1 = 1 / m1, w2 = 1 / m2;
      Vec2 x1e = x1, x2e = x2, v1e = v1, v2e = v2;
      double Je = 0;
      if (sgap >= 0) {
        if (vn < 0) {
          Je = -(1 + e) * vn / (w1 + w2);
          v1e += (Je / m1) * n;
          v2e -= (Je / m2) * n;
        }
        x1e += sgap * w1 / (w1 + w2) * n;
        x2e -= sgap * w2 / (w1 + w2) * n;
      }
      Vec2 y1 = x1, y2 = x2, u1 = v1, u2 = v2;
      const double J = collide_particles(m1, r1, m2, r2, e, y1, u1, y2, u2);
      INFO("m1 = " << m1 << ", r1 = " << r1 << ", x1 = " << wbtest::str(x1)
                   << ", v1 = " << wbtest::str(v1) << "; m2 = " << m2 << ", r2 = " << r2
                   << ", x2 = " << wbtest::str(x2) << ", v2 = " << wbtest::str(v2)
                   << "; e = " << e << " (overlap " << sgap << ", (v1 - v2).n = " << vn << ")");
      const double scale = 1.0 + x1.norm() + x2.norm() + v1.norm() + v2.norm();
      wbtest::require_near(J, Je, 1e-12 * (1 + std::abs(Je)),
                           "J = -(1 + e) v_n / (1/m1 + 1/m2) in contact and approaching, else 0");
      wbtest::require_near(u1, v1e, 1e-12 * scale, "v1 + (J / m1) n");
      wbtest::require_near(u2, v2e, 1e-12 * scale, "v2 - (J / m2) n");
      wbtest::require_near(y1, x1e, 1e-12 * scale, "x1 moved out by s w1 / (w1 + w2) along n");
      wbtest::require_near(y2, x2e, 1e-12 * scale, "x2 moved out by s w2 / (w1 + w2) against n");
    };
    for (int s = 0; s < 16; ++s) {
      const double m1 = g.log_uniform(0.05, 20.0), m2 = g.log_uniform(0.05, 20.0);
      const double e = g.uniform(0.0, 1.0);
      const bool exact = s % 4 == 0;  // touching exactly: binary fractions along an axis
      const double r1 = exact ? g.integer(0, 8) / 8.0 : g.uniform(0.0, 1.0);
      const double r2 = exact ? g.integer(1, 8) / 8.0 : g.uniform(0.05, 1.0);
      const Vec2 x2 =
          exact ? Vec2(g.integer(-8, 8) / 8.0, g.integer(-8, 8) / 8.0) : Vec2(g.vec2(-2, 2));
      Vec2 x1;
      if (exact) {
        x1 = x2 + (r1 + r2) * (g.coin() ? Vec2(g.sign(), 0) : Vec2(0, g.sign()));
      } else if (s % 4 == 1) {
        x1 = x2;  // coincident centres: the fallback normal (0, 1)
      } else {
        x1 = x2 + (r1 + r2) * g.uniform(0.3, 1.3) * g.unit2();  // overlapping or apart
      }
      check(m1, r1, m2, r2, e, x1, x2, g.vec2(-3, 3), g.vec2(-3, 3));
    }
    // Overlapping, the two moving the same way along n: approaching (relative velocity
    // against n) while disc 1 moves along n, and separating while disc 1 moves against n.
    for (const double sense : {1.0, -1.0}) {
      const double r1 = g.uniform(0.1, 1.0), r2 = g.uniform(0.1, 1.0);
      const Vec2 x2 = g.vec2(-2, 2), n = g.unit2(), t(-n.y(), n.x());
      const Vec2 x1 = x2 + (r1 + r2) * g.uniform(0.5, 0.95) * n;
      const double a = g.uniform(0.5, 2.0), b = g.uniform(0.5, 2.0);
      const Vec2 v1 = sense * a * n + g.uniform(-2, 2) * t;
      const Vec2 v2 = sense * (a + b) * n + g.uniform(-2, 2) * t;
      check(g.log_uniform(0.05, 20.0), r1, g.log_uniform(0.05, 20.0), r2, g.uniform(0.2, 1.0), x1,
            x2, v1, v2);
    }
  }
}

}  // namespace test_C2_collide_particles
