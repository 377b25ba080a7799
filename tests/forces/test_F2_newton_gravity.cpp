// F2 Newtonian gravitation between all pairs, softened by eps
// (labs/forces/newton_gravity.h).
#include <cmath>

#include "heldout.h"
#include "newton_gravity.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F2_newton_gravity {

using wb::Mat2X;
using wb::Vec2;
using wb::VecX;

namespace {

// Hand-derived values below are exact decimals or simple fractions: rounding only.
constexpr double kTol = 1e-12;

// The header's formula, written out directly: every ordered pair j != i.
Mat2X newton_reference(const Mat2X& x, const VecX& m, double G, double eps) {
  Mat2X f = Mat2X::Zero(2, x.cols());
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      if (j == i) continue;
      const Vec2 d = x.col(j) - x.col(i);
      const double s = d.squaredNorm() + eps * eps;
      f.col(i) += G * m[i] * m[j] * d / std::pow(s, 1.5);
    }
  }
  return f;
}

// V = - sum_{i<j} G m_i m_j / sqrt(r_ij^2 + eps^2), from the header.
double newton_potential(const Mat2X& x, const VecX& m, double G, double eps) {
  double V = 0;
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    for (Eigen::Index j = i + 1; j < x.cols(); ++j) {
      V -= G * m[i] * m[j] / std::sqrt((x.col(j) - x.col(i)).squaredNorm() + eps * eps);
    }
  }
  return V;
}

Mat2X two(const Vec2& a, const Vec2& b) {
  Mat2X x(2, 2);
  x.col(0) = a;
  x.col(1) = b;
  return x;
}

}  // namespace

TEST_CASE("F2 newton gravity: two bodies attract with G m_i m_j d / r^3", "[forces][F2][3pts]") {
  // x_0 = (1, 2), x_1 = (4, 6): d = x_1 - x_0 = (3, 4), r = 5, r^3 = 125.
  // m = (2, 3), G = 0.5, eps = 0: G m_0 m_1 / r^3 = 3 / 125, so
  // f_0 = 3 (3, 4) / 125 = (0.072, 0.096) towards x_1, and f_1 = -f_0.
  const Mat2X x = two(Vec2(1, 2), Vec2(4, 6));
  VecX m(2);
  m << 2.0, 3.0;
  Mat2X f = Mat2X::Zero(2, 2);
  add_newton_gravity(x, m, 0.5, 0.0, f);
  wbtest::require_near(Vec2(f.col(0)), Vec2(0.072, 0.096), kTol,
                       "gravity pulls body 0 towards body 1 with G m_0 m_1 / r^2", kTol);
  wbtest::require_near(Vec2(f.col(1)), Vec2(-0.072, -0.096), kTol,
                       "gravity pulls body 1 towards body 0 (Newton's third law: f_1 = -f_0)",
                       kTol);
}

TEST_CASE("F2 newton gravity: softening replaces r^2 by r^2 + eps^2", "[forces][F2][2pts]") {
  // x_0 = (-1, 0.5), x_1 = (2, 4.5): d = (3, 4), r^2 = 25. eps = sqrt(11), so
  // r^2 + eps^2 = 36 and (r^2 + eps^2)^(3/2) = 216.
  // m = (0.5, 4), G = 3: G m_0 m_1 = 6, f_0 = 6 (3, 4) / 216 = (1/12, 1/9), f_1 = -f_0.
  // (eps instead of eps^2 would give 25 + 3.32 in place of 36.)
  const Mat2X x = two(Vec2(-1, 0.5), Vec2(2, 4.5));
  VecX m(2);
  m << 0.5, 4.0;
  Mat2X f = Mat2X::Zero(2, 2);
  add_newton_gravity(x, m, 3.0, std::sqrt(11.0), f);
  wbtest::require_near(Vec2(f.col(0)), Vec2(1.0 / 12, 1.0 / 9), kTol,
                       "softened gravity on body 0: G m_0 m_1 d / (r^2 + eps^2)^(3/2)", kTol);
  wbtest::require_near(Vec2(f.col(1)), Vec2(-1.0 / 12, -1.0 / 9), kTol,
                       "softened gravity on body 1: equal and opposite (third law)", kTol);
}

TEST_CASE("F2 newton gravity: adds to the forces already there", "[forces][F2][1pts]") {
  // The pair of the first test (f_0 = (0.072, 0.096)) on top of existing forces.
  const Mat2X x = two(Vec2(1, 2), Vec2(4, 6));
  VecX m(2);
  m << 2.0, 3.0;
  Mat2X f(2, 2);
  f << 1.0, -2.0,  //
      0.5, 3.0;
  add_newton_gravity(x, m, 0.5, 0.0, f);
  Mat2X expected(2, 2);
  expected << 1.072, -2.072,  //
      0.596, 2.904;
  wbtest::require_near(f, expected, kTol,
                       "forces add up (superposition): f must keep what other terms put there",
                       kTol);
}

TEST_CASE("F2 newton gravity: pair forces cancel so a cluster keeps its momentum",
          "[forces][F2][2pts]") {
  // 12 bodies of different masses at random: the net force is a sum of
  // pairs f_ij + f_ji = 0, so it vanishes up to rounding (relative 1e-15 per
  // term, a few dozen terms: 1e-12 of the total force magnitude is ample).
  const Eigen::Index n = 12;
  const Mat2X x = wbtest::random_points(n, 2024, -1.0, 1.0);
  const Mat2X mu = wbtest::random_points(n, 7, 0.5, 2.0);
  const VecX m = mu.row(0).transpose();
  const double G = 1.3, eps = 0.05;
  Mat2X f = Mat2X::Zero(2, n);
  add_newton_gravity(x, m, G, eps, f);
  const Mat2X expected = newton_reference(x, m, G, eps);
  const double scale = expected.colwise().norm().sum();
  const Vec2 net = f.rowwise().sum();
  wbtest::require_near(net, Vec2::Zero(), 1e-12 * scale,
                       "Newton's third law: the net internal force of a closed system is zero, "
                       "so its momentum is constant");
  wbtest::require_near(f, expected, 1e-12 * scale,
                       "each body feels sum_{j != i} G m_i m_j (x_j - x_i) / (r^2 + eps^2)^(3/2)",
                       1e-12);
}

TEST_CASE("F2 newton gravity: the force is minus the gradient of the softened potential",
          "[forces][F2][2pts]") {
  // Four bodies at least 0.99 apart, eps = 0.1. Central differences with
  // h = 1e-5: truncation h^2/6 |V'''| ~ 1e-10 / 6 * 6 G m_i m_j / r^4 < 1e-8 here,
  // rounding eps_mach |V| / h ~ 1e-16 * 5 / 1e-5 = 5e-11; tolerance 1e-7.
  Mat2X x(2, 4);
  x << 0.3, 1.1, -0.5, 0.2,  //
      -0.2, 0.4, 0.9, 1.6;
  VecX m(4);
  m << 1.0, 2.5, 0.4, 1.7;
  const double G = 0.7, eps = 0.1, h = 1e-5, tol = 1e-7;
  const Mat2X expected = wbtest::minus_gradient(
      [&](const Mat2X& y) { return newton_potential(y, m, G, eps); }, x, h);
  Mat2X f = Mat2X::Zero(2, 4);
  add_newton_gravity(x, m, G, eps, f);
  wbtest::require_near(f, expected, tol,
                       "gravity is conservative: f = -dV/dx with "
                       "V = -sum_{i<j} G m_i m_j / sqrt(r^2 + eps^2)",
                       tol);
}

TEST_CASE("F2 newton gravity: coincident bodies give finite forces with and without softening",
          "[forces][F2][2pts]") {
  // Bodies 0 and 1 both at (1, 1), body 2 at (4, 5): d = (3, 4) from either to
  // body 2, r = 5. m = (1, 2, 3), G = 0.5. The coincident pair adds nothing:
  //   eps = 0:        d = 0 and r^2 + eps^2 = 0, the header says skip it;
  //   eps = sqrt(11): d = 0 so G m_0 m_1 d / eps^3 = 0.
  Mat2X x(2, 3);
  x << 1, 1, 4,  //
      1, 1, 5;
  VecX m(3);
  m << 1.0, 2.0, 3.0;
  const double G = 0.5;

  // eps = 0: G m_0 m_2 / 125 = 1.5 / 125, G m_1 m_2 / 125 = 3 / 125.
  Mat2X f = Mat2X::Zero(2, 3);
  add_newton_gravity(x, m, G, 0.0, f);
  wbtest::require_finite(f, "unsoftened gravity with two coincident bodies");
  Mat2X expected(2, 3);
  expected << 0.036, 0.072, -0.108,  //
      0.048, 0.096, -0.144;
  wbtest::require_near(f, expected, kTol,
                       "eps = 0: a coincident pair adds nothing, the others still attract", kTol);

  // eps = sqrt(11): r^2 + eps^2 = 36, 36^(3/2) = 216: 1.5 (3, 4) / 216 and 3 (3, 4) / 216.
  f.setZero();
  add_newton_gravity(x, m, G, std::sqrt(11.0), f);
  wbtest::require_finite(f, "softened gravity with two coincident bodies");
  expected << 4.5 / 216, 9.0 / 216, -13.5 / 216,  //
      6.0 / 216, 12.0 / 216, -18.0 / 216;
  wbtest::require_near(f, expected, kTol,
                       "eps > 0: a coincident pair has d = 0 so adds nothing, the others attract",
                       kTol);
}

TEST_CASE("F2 held-out: random clusters attract pairwise with G m_i m_j d / (r^2 + eps^2)^(3/2)",
          "[forces][F2][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F2")) {
    INFO(g.replay());
    // One cluster unsoftened and one softened, each with two bodies at the same place
    // (a coincident pair adds nothing, with or without softening).
    for (const bool soft : {false, true}) {
      const Eigen::Index n = g.integer(4, 9);
      Mat2X x = g.points(n, -3.0, 3.0);
      const Eigen::Index a = g.integer(0, n - 1), b = (a + g.integer(1, n - 1)) % n;
      x.col(b) = x.col(a);
      const VecX m = g.values(n, 0.2, 4.0);
      const double G = g.uniform(0.1, 3.0), eps = soft ? g.uniform(0.05, 0.6) : 0.0;
      const Mat2X f0 = g.points(n, -5.0, 5.0);
      Mat2X f = f0;
      add_newton_gravity(x, m, G, eps, f);
      Mat2X expected = f0;
      double scale = 0;
      for (Eigen::Index i = 0; i < n; ++i) {
        for (Eigen::Index j = 0; j < n; ++j) {
          const Vec2 d = x.col(j) - x.col(i);
          const double s = d.squaredNorm() + eps * eps;
          if (j == i || s == 0.0) continue;
          const Vec2 fij = G * m[i] * m[j] * d / std::pow(s, 1.5);
          expected.col(i) += fij;
          scale += fij.norm();
        }
      }
      INFO("x = " << x << "\n  m = " << m.transpose() << ", G = " << G << ", eps = " << eps
                  << " (bodies " << a << " and " << b << " coincide)");
      wbtest::require_near(f, expected, 1e-12 * (1.0 + scale),
                           "each body gets sum_{j != i} G m_i m_j (x_j - x_i) / "
                           "(r^2 + eps^2)^(3/2), added to f",
                           1e-12);
    }
  }
}

}  // namespace test_F2_newton_gravity
