// Graded tests for I1, backward Euler for one spring solved by hand
// (labs/implicit/backward_euler_spring.cpp). Expected values: the two defining
// equations solved as a linear system, the eigenvalues of the step on an
// undamped spring, and the exact oscillator x(t) = x0 cos wt + v0/w sin wt.
#include <Eigen/Dense>

#include "backward_euler_spring.h"
#include "implicit_checks.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_I1_backward_euler_spring {

namespace {
using wb::Vec2;

// Rounding: a step is a dozen operations on O(1..1e6) numbers; results are
// compared relative to their size with a margin of ~1000 ulps.
constexpr double kRelTol = 1e-12;
}  // namespace

TEST_CASE("I1 one spring: one step solves the two backward Euler equations",
          "[implicit][I1][6pts]") {
  const double m = 2.0, k = 50.0, b = 0.7, h = 0.05;
  const Vec2 c(0.3, -0.2), f(0.5, -19.6);
  Vec2 x(1.1, 0.4), v(-0.6, 2.1);
  // Per coordinate: x' - h v' = x and (h k/m) x' + (1 + h b/m) v' = v + h (k c + f)/m.
  Vec2 xe, ve;
  for (int d = 0; d < 2; ++d) {
    Eigen::Matrix2d A;
    A << 1.0, -h, h * k / m, 1.0 + h * b / m;
    const Eigen::Vector2d r(x[d], v[d] + h * (k * c[d] + f[d]) / m);
    const Eigen::Vector2d s = imtest::solve2(A, r);
    xe[d] = s[0];
    ve[d] = s[1];
  }
  backward_euler_spring_step(m, k, b, c, f, h, x, v);
  wbtest::require_near(
      x, xe, 0.0, "x' from x' = x + h v' and m v' = m v + h (-k (x'-c) - b v' + f)", kRelTol);
  wbtest::require_near(v, ve, 0.0, "v' from the same two equations", kRelTol);
}

TEST_CASE("I1 one spring: energy shrinks by 1/(1 + (h w)^2) per step at any h w",
          "[implicit][I1][7pts]") {
  // Undamped: the step matrix has eigenvalues 1/(1 -+ i h w), of modulus^2
  // 1/(1 + (h w)^2), and it maps the energy ellipse onto a scaled copy.
  // Tolerance 1e-8: at h w = 1e3, x' = x + h v' cancels three digits (x' is 1e-3
  // of x), so x' carries ~1e3 ulps and the energy ratio twice that.
  const double m = 0.5, k = 8.0, w = std::sqrt(k / m);
  const Vec2 c(0.2, 0.1);
  for (double hw : {0.1, 1.0, 10.0, 1000.0}) {
    const double h = hw / w;
    Vec2 x(1.0, 0.5), v(0.3, -2.0);
    auto E = [&] { return 0.5 * m * v.squaredNorm() + 0.5 * k * (x - c).squaredNorm(); };
    for (int step = 0; step < 3; ++step) {
      const double E0 = E();
      backward_euler_spring_step(m, k, 0.0, c, Vec2::Zero(), h, x, v);
      wbtest::require_near(E() / E0, 1.0 / (1.0 + hw * hw), 0.0,
                           "energy ratio of one step at h w = " + std::to_string(hw), 1e-8);
    }
  }
}

TEST_CASE("I1 one spring: first order in h against the exact oscillator",
          "[implicit][I1][4pts]") {
  // w = 2 pi, T = 0.5: error ~ C h (1 + O(w^2 h)), so log2(e(h)/e(h/2)) = 1 + O(0.02) for
  // N >= 400; a window of 0.1 rejects order 0 (inconsistent) and order 2.
  const double m = 1.0, w = 2.0 * M_PI, k = w * w * m, T = 0.5;
  const Vec2 x0(1.0, 0.0), v0(0.0, 3.0);
  auto error = [&](int N) {
    Vec2 x = x0, v = v0;
    for (int s = 0; s < N; ++s)
      backward_euler_spring_step(m, k, 0.0, Vec2::Zero(), Vec2::Zero(), T / N, x, v);
    const Vec2 xe = x0 * std::cos(w * T) + v0 / w * std::sin(w * T);
    return (x - xe).norm();
  };
  double prev = error(400);
  for (int N : {800, 1600}) {
    const double e = error(N), p = std::log2(prev / e);
    INFO("measured order " << p << " from " << N / 2 << " to " << N << " steps, expected 1");
    REQUIRE(std::isfinite(p));
    REQUIRE(std::abs(wbtest::finite(p) - 1.0) <= 0.1);
    prev = e;
  }
}

TEST_CASE("I1 held-out: random springs solve (m + h b + h^2 k) v' = m v - h k (x - c) + h f_ext",
          "[implicit][I1][held-out][3pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("I1")) {
    INFO(g.replay());
    for (int s = 0; s < 6; ++s) {
      const double m = g.uniform(0.1, 5.0), k = g.log_uniform(0.1, 1e4),
                   b = s == 0 ? 0.0 : g.uniform(0.0, 3.0), h = g.log_uniform(1e-3, 1.0);
      const Vec2 c = g.vec2(-2, 2), f = s == 1 ? Vec2(0, 0) : Vec2(g.vec2(-20, 20));
      Vec2 x = g.vec2(-3, 3), v = g.vec2(-5, 5);
      const Vec2 x0 = x, v0 = v;
      const Vec2 ve = (m * v0 - h * k * (x0 - c) + h * f) / (m + h * b + h * h * k);
      const Vec2 xe = x0 + h * ve;
      backward_euler_spring_step(m, k, b, c, f, h, x, v);
      INFO("m = " << m << ", k = " << k << ", b = " << b << ", c = " << wbtest::str(c)
                  << ", f_ext = " << wbtest::str(f) << ", h = " << h
                  << ", x = " << wbtest::str(x0) << ", v = " << wbtest::str(v0));
      const double scale = x0.norm() + c.norm() + h * v0.norm() + h * h * f.norm() / m;
      wbtest::require_near(v, ve, kRelTol * (v0.norm() + (k * scale + f.norm()) * h / m),
                           "v' = (m v - h k (x - c) + h f_ext) / (m + h b + h^2 k)", kRelTol);
      wbtest::require_near(x, xe, kRelTol * scale, "x' = x + h v'", kRelTol);
    }
  }
}

}  // namespace test_I1_backward_euler_spring
