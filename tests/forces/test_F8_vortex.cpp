// F8 vortex field: a Rankine vortex u(x) and the drag f_i += c (u(x_i) - v_i)
// (labs/forces/vortex.h).
#include "heldout.h"
#include "test_helpers.h"
#include "vortex.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F8_vortex {

using wb::Mat2X;
using wb::Vec2;

namespace {

// Hand-derived values below are short decimals: rounding only.
constexpr double kTol = 1e-12;

// The vortex of most tests: centre off the origin, core radius R = 2 (not 1,
// so R^2 / r and R^2 / r^2 differ at the core's edge), omega = 2.
VortexParams vortex() {
  VortexParams p;
  p.center = Vec2(1, -1);
  p.omega = 2.0;
  p.core = 2.0;
  p.drag = 1.5;
  return p;
}

}  // namespace

TEST_CASE("F8 vortex: inside the core the flow turns like a solid disc", "[forces][F8][2pts]") {
  const VortexParams p = vortex();
  // x = (1.6, -0.2): d = (0.6, 0.8), r = 1 < R, perp(d) = (-0.8, 0.6),
  // u = omega perp(d) = (-1.6, 1.2), speed omega r = 2.
  wbtest::require_near(vortex_flow(Vec2(1.6, -0.2), p), Vec2(-1.6, 1.2), kTol,
                       "solid rotation in the core: u = omega perp(x - center), speed omega r",
                       kTol);
  // x = (0.1, -2.2): d = (-0.9, -1.2), r = 1.5 < R, perp(d) = (1.2, -0.9),
  // u = (2.4, -1.8), speed omega r = 3.
  wbtest::require_near(vortex_flow(Vec2(0.1, -2.2), p), Vec2(2.4, -1.8), kTol,
                       "solid rotation in the core: u = omega perp(x - center), speed omega r",
                       kTol);
}

TEST_CASE("F8 vortex: outside the core the speed falls off as omega R^2 / r",
          "[forces][F8][2pts]") {
  const VortexParams p = vortex();
  // x = (4, 3): d = (3, 4), r = 5 > R, perp(d) = (-4, 3),
  // u = omega R^2 perp(d) / r^2 = 8 (-4, 3) / 25 = (-1.28, 0.96), speed 8 / 5 = omega R^2 / r.
  wbtest::require_near(vortex_flow(Vec2(4, 3), p), Vec2(-1.28, 0.96), kTol,
                       "irrotational outside: u = omega R^2 perp(d) / r^2, speed omega R^2 / r",
                       kTol);
  // x = (-1.4, 0.8): d = (-2.4, 1.8), r = 3, perp(d) = (-1.8, -2.4),
  // u = 8 (-1.8, -2.4) / 9 = (-1.6, -32/15), speed 8 / 3.
  wbtest::require_near(vortex_flow(Vec2(-1.4, 0.8), p), Vec2(-1.6, -32.0 / 15), kTol,
                       "irrotational outside: u = omega R^2 perp(d) / r^2, speed omega R^2 / r",
                       kTol);
}

TEST_CASE("F8 vortex: the flow is continuous at the core radius and zero at the centre",
          "[forces][F8][1pts]") {
  const VortexParams p = vortex();
  // Along the unit direction (0.6, -0.8), just inside and just outside r = R = 2.
  // Both formulas give omega R perp(unit) = 4 (0.8, 0.6) = (3.2, 2.4) at r = R; a
  // step of 2e-9 in r changes u by at most omega * 2e-9 ~ 4e-9: tolerance 1e-7.
  const Vec2 unit(0.6, -0.8), on_core(3.2, 2.4);
  const double tol = 1e-7;
  const Vec2 u_in = vortex_flow(p.center + (p.core * (1 - 1e-9)) * unit, p);
  const Vec2 u_out = vortex_flow(p.center + (p.core * (1 + 1e-9)) * unit, p);
  wbtest::require_near(u_in, on_core, tol, "just inside the core: u = omega R perp(unit)");
  wbtest::require_near(
      u_out, on_core, tol,
      "just outside the core: u = omega R^2 perp(d) / r^2 -> omega R perp(unit), "
      "the same as inside (a Rankine vortex has no jump)");

  // The axis itself does not move.
  const Vec2 u0 = vortex_flow(p.center, p);
  {
    INFO("flow at the centre gave " << wbtest::str(u0));
    REQUIRE(u0.allFinite());
  }
  wbtest::require_near(u0, Vec2(0, 0), 0.0, "the vortex axis is at rest: u(center) = 0");
}

TEST_CASE("F8 vortex: drag c (u - v) towards the flow is zero for a particle moving with it",
          "[forces][F8][3pts]") {
  const VortexParams p = vortex();  // c = 1.5
  // The first and the last particle feel a non-zero drag, so that a loop
  // that skips either end leaves a column wrong.
  // Particle 0 at (4, 3) at rest: f = 1.5 (-1.28, 0.96) = (-1.92, 1.44).
  // Particle 1 at (1.6, -0.2) moves with the flow, v = u = (-1.6, 1.2): no force.
  // Particle 2 on the axis at rest: u = 0, v = 0, no force.
  // Particle 3 at (0.1, -2.2), v = (1, 1): f = 1.5 ((2.4, -1.8) - (1, 1)) = (2.1, -4.2).
  Mat2X x(2, 4), v(2, 4), f(2, 4);
  x << 4.0, 1.6, 1.0, 0.1,  //
      3.0, -0.2, -1.0, -2.2;
  v << 0.0, -1.6, 0.0, 1.0,  //
      0.0, 1.2, 0.0, 1.0;
  f << 2.0, 1.0, 4.0, 3.0,  // forces already there: add to them
      0.0, -1.0, 0.25, 0.5;
  add_vortex(x, v, p, f);
  wbtest::require_finite(f, "vortex drag with a particle on the axis");
  Mat2X expected(2, 4);
  expected << 2.0 - 1.92, 1.0, 4.0, 3.0 + 2.1,  //
      1.44, -1.0, 0.25, 0.5 - 4.2;
  wbtest::require_near(f, expected, kTol,
                       "drag towards the flow: f_i += c (u(x_i) - v_i) for EVERY particle i "
                       "(first and last included), added to f",
                       kTol);
}

TEST_CASE("F8 vortex: omega > 0 turns counter-clockwise and omega < 0 clockwise",
          "[forces][F8][1pts]") {
  VortexParams p = vortex();
  const Mat2X pts = wbtest::random_points(8, 41, -4.0, 4.0);
  for (double omega : {2.0, -1.5}) {
    p.omega = omega;
    for (Eigen::Index i = 0; i < pts.cols(); ++i) {
      const Vec2 d = Vec2(pts.col(i)) - p.center;
      if (d.norm() < 1e-3) continue;
      const double turn = wb::cross(d, vortex_flow(pts.col(i), p));  // > 0: counter-clockwise
      CAPTURE(omega, i, turn);
      INFO(
          "the flow must turn in the sense of omega: cross(x - center, u) has the sign of omega");
      REQUIRE(wbtest::finite(turn) * omega > 0);
    }
  }
  // omega = -1.5 at (4, 3): -1.5 * 4 (-4, 3) / 25 = (0.96, -0.72).
  wbtest::require_near(vortex_flow(Vec2(4, 3), p), Vec2(0.96, -0.72), kTol,
                       "omega < 0: the same flow reversed", kTol);
}

TEST_CASE("F8 held-out: random vortices and particles inside and outside the core",
          "[forces][F8][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F8")) {
    INFO(g.replay());
    // Both senses of turning in every draw: omega's sign says which way the flow turns.
    for (const double sense : {1.0, -1.0}) {
      VortexParams p;
      p.center = g.vec2(-2.0, 2.0);
      p.omega = sense * g.uniform(0.2, 4.0);
      p.core = g.uniform(0.5, 2.5);
      p.drag = g.uniform(0.1, 3.0);
      const Eigen::Index n = g.integer(4, 10);
      // Half of them inside the core, half outside, one on the axis.
      Mat2X x(2, n);
      for (Eigen::Index i = 0; i < n; ++i)
        x.col(i) = p.center +
                   (i % 2 ? g.uniform(0.05, 0.95) : g.uniform(1.05, 3.0)) * p.core * g.unit2();
      x.col(g.integer(0, n - 1)) = p.center;
      const Mat2X v = g.points(n, -3.0, 3.0), f0 = g.points(n, -5.0, 5.0);
      Mat2X expected = f0;
      for (Eigen::Index i = 0; i < n; ++i) {
        const Vec2 d = x.col(i) - p.center, perp(-d.y(), d.x());
        const double r = d.norm();
        const Vec2 u =
            r <= p.core ? Vec2(p.omega * perp) : Vec2(p.omega * p.core * p.core * perp / (r * r));
        INFO("x = " << wbtest::str(x.col(i)) << ", center " << wbtest::str(p.center)
                    << ", omega = " << p.omega << ", core R = " << p.core);
        wbtest::require_near(
            vortex_flow(x.col(i), p), u, 1e-12 * (1.0 + u.norm()),
            "Rankine vortex: omega perp(d) inside, omega R^2 perp(d) / r^2 outside", 1e-12);
        expected.col(i) += p.drag * (u - v.col(i));
      }
      Mat2X f = f0;
      add_vortex(x, v, p, f);
      INFO("x = " << x << "\n  v = " << v << "\n  drag c = " << p.drag);
      wbtest::require_near(f, expected, 1e-11, "f_i += c (u(x_i) - v_i) for every particle",
                           1e-12);
    }
  }
}

}  // namespace test_F8_vortex
