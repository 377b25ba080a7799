// F2 Newtonian gravitation between all pairs, softened by eps
// (labs/forces/newton_gravity.h).
#include <cmath>

#include "heldout.h"
#include "newton_gravity.h"
#include "params.h"
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

// The header's law with the coincident pairs skipped (r^2 + eps^2 = 0: no direction, no
// force), added to f0; `scale` gets the sum of the pair forces' magnitudes.
Mat2X newton_law(const Mat2X& x, const VecX& m, double G, double eps, const Mat2X& f0,
                 double& scale) {
  Mat2X f = f0;
  scale = 0;
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      const Vec2 d = x.col(j) - x.col(i);
      const double s = d.squaredNorm() + eps * eps;
      if (j == i || s == 0.0) continue;
      const Vec2 fij = G * m[i] * m[j] * d / std::pow(s, 1.5);
      f.col(i) += fij;
      scale += fij.norm();
    }
  }
  return f;
}

// The scenarios of the public tests below, each a function of its parameters: the public test
// runs it with the published ones (wbtest::Params()), the held-out test with drawn ones, in the
// same format (tests/common/params.h): short decimals where the published values are (eps as
// the square root of one), the published particle counts (the cluster's within 1), points from
// a drawn seed where the public test draws its own, about the published magnitudes.

// The first test's pair: x_0 = (1, 2), x_1 = (4, 6), m = (2, 3), G = 0.5. Held-out: each drawn
// about it (r about 5, distinct masses).
struct Pair {
  Mat2X x;
  VecX m;
  double G;
  explicit Pair(const wbtest::Params& p)
      : x(two(Vec2(p.num(1.0, 0.5, 1.5), p.num(2.0, 1.5, 2.5)),
              Vec2(p.num(4.0, 3.5, 4.5), p.num(6.0, 5.5, 6.5)))),
        m(2),
        G(p.num(0.5, 0.3, 0.7)) {
    m << p.num(2.0, 1.5, 2.5), p.num(3.0, 2.6, 3.5);
  }
};

void two_bodies(const wbtest::Params& p) {
  // x_0 = (1, 2), x_1 = (4, 6): d = x_1 - x_0 = (3, 4), r = 5, r^3 = 125.
  // m = (2, 3), G = 0.5, eps = 0: G m_0 m_1 / r^3 = 3 / 125, so
  // f_0 = 3 (3, 4) / 125 = (0.072, 0.096) towards x_1, and f_1 = -f_0.
  const Pair q(p);
  Mat2X f = Mat2X::Zero(2, 2);
  add_newton_gravity(q.x, q.m, q.G, 0.0, f);
  double scale = 0;
  const Mat2X e = newton_law(q.x, q.m, q.G, 0.0, Mat2X::Zero(2, 2), scale);
  wbtest::require_near(Vec2(f.col(0)), Vec2(e.col(0)), kTol,
                       "gravity pulls body 0 towards body 1 with G m_0 m_1 / r^2", kTol);
  wbtest::require_near(Vec2(f.col(1)), Vec2(e.col(1)), kTol,
                       "gravity pulls body 1 towards body 0 (Newton's third law: f_1 = -f_0)",
                       kTol);
}

void softening(const wbtest::Params& p) {
  // x_0 = (-1, 0.5), x_1 = (2, 4.5): d = (3, 4), r^2 = 25. eps = sqrt(11), so
  // r^2 + eps^2 = 36 and (r^2 + eps^2)^(3/2) = 216.
  // m = (0.5, 4), G = 3: G m_0 m_1 = 6, f_0 = 6 (3, 4) / 216 = (1/12, 1/9), f_1 = -f_0.
  // (eps instead of eps^2 would give 25 + 3.32 in place of 36.)
  // Held-out: each drawn about it, eps^2 from 8 to 14.
  const Mat2X x = two(Vec2(p.num(-1.0, -1.5, -0.5), p.num(0.5, 0.0, 1.0)),
                      Vec2(p.num(2.0, 1.5, 2.5), p.num(4.5, 4.0, 5.0)));
  VecX m(2);
  m << p.num(0.5, 0.3, 0.8), p.num(4.0, 3.0, 5.0);
  const double G = p.num(3.0, 2.0, 4.0), eps = std::sqrt(p.num(11.0, 8.0, 14.0));
  Mat2X f = Mat2X::Zero(2, 2);
  add_newton_gravity(x, m, G, eps, f);
  double scale = 0;
  const Mat2X e = newton_law(x, m, G, eps, Mat2X::Zero(2, 2), scale);
  wbtest::require_near(Vec2(f.col(0)), Vec2(e.col(0)), kTol,
                       "softened gravity on body 0: G m_0 m_1 d / (r^2 + eps^2)^(3/2)", kTol);
  wbtest::require_near(Vec2(f.col(1)), Vec2(e.col(1)), kTol,
                       "softened gravity on body 1: equal and opposite (third law)", kTol);
}

void adds_up(const wbtest::Params& p) {
  // The pair of the first test (f_0 = (0.072, 0.096)) on top of existing forces:
  // (1.072, 0.596) and (-2.072, 2.904).
  const Pair q(p);
  Mat2X f(2, 2);
  f << p.num(1.0, 0.5, 1.5), p.num(-2.0, -2.5, -1.5),  //
      p.num(0.5, 0.2, 0.8), p.num(3.0, 2.5, 3.5);
  const Mat2X f0 = f;
  add_newton_gravity(q.x, q.m, q.G, 0.0, f);
  double scale = 0;
  wbtest::require_near(f, newton_law(q.x, q.m, q.G, 0.0, f0, scale), kTol,
                       "forces add up (superposition): f must keep what other terms put there",
                       kTol);
}

void cluster(const wbtest::Params& p) {
  // 12 bodies of different masses at random: the net force is a sum of
  // pairs f_ij + f_ji = 0, so it vanishes up to rounding (relative 1e-15 per
  // term, a few dozen terms: 1e-12 of the total force magnitude is ample).
  // Held-out: 11 to 13 bodies, the points' and masses' seeds, G and eps drawn.
  const Eigen::Index n = p.count(12, 11, 13);
  const Mat2X x = wbtest::random_points(n, std::uint64_t(p.count(2024, 1, 1000000)), -1.0, 1.0);
  const Mat2X mu = wbtest::random_points(n, std::uint64_t(p.count(7, 1, 1000000)), 0.5, 2.0);
  const VecX m = mu.row(0).transpose();
  const double G = p.num(1.3, 0.8, 1.8), eps = p.num(0.05, 0.03, 0.08);
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

void minus_gradient(const wbtest::Params& p) {
  // Four bodies at least 0.99 apart (held-out: each coordinate within 0.05 of the published
  // one, so at least 0.84), eps = 0.1. Central differences with h = 1e-5: truncation
  // h^2/6 |V'''| ~ 1e-10 / 6 * 6 G m_i m_j / r^4 < 1e-8 here, rounding
  // eps_mach |V| / h ~ 1e-16 * 5 / 1e-5 = 5e-11; tolerance 1e-7.
  Mat2X x(2, 4);
  x << p.num(0.3, 0.25, 0.35), p.num(1.1, 1.05, 1.15), p.num(-0.5, -0.55, -0.45),
      p.num(0.2, 0.15, 0.25),  //
      p.num(-0.2, -0.25, -0.15), p.num(0.4, 0.35, 0.45), p.num(0.9, 0.85, 0.95),
      p.num(1.6, 1.55, 1.65);
  VecX m(4);
  m << p.num(1.0, 0.8, 1.2), p.num(2.5, 2.0, 3.0), p.num(0.4, 0.3, 0.5), p.num(1.7, 1.4, 2.0);
  const double G = p.num(0.7, 0.5, 0.9), eps = p.num(0.1, 0.08, 0.12), h = 1e-5, tol = 1e-7;
  const Mat2X expected = wbtest::minus_gradient(
      [&](const Mat2X& y) { return newton_potential(y, m, G, eps); }, x, h);
  Mat2X f = Mat2X::Zero(2, 4);
  add_newton_gravity(x, m, G, eps, f);
  wbtest::require_near(f, expected, tol,
                       "gravity is conservative: f = -dV/dx with "
                       "V = -sum_{i<j} G m_i m_j / sqrt(r^2 + eps^2)",
                       tol);
}

void coincident(const wbtest::Params& p) {
  // Bodies 0 and 1 both at (1, 1), body 2 at (4, 5): d = (3, 4) from either to
  // body 2, r = 5. m = (1, 2, 3), G = 0.5. The coincident pair adds nothing:
  //   eps = 0:        d = 0 and r^2 + eps^2 = 0, the header says skip it;
  //   eps = sqrt(11): d = 0 so G m_0 m_1 d / eps^3 = 0.
  // Held-out: each drawn about it (bodies 0 and 1 still at the same place), eps^2 from 8 to 14.
  Mat2X x(2, 3);
  const Vec2 at(p.num(1.0, 0.5, 1.5), p.num(1.0, 0.5, 1.5));
  x.col(0) = at;
  x.col(1) = at;
  x.col(2) = Vec2(p.num(4.0, 3.5, 4.5), p.num(5.0, 4.5, 5.5));
  VecX m(3);
  m << p.num(1.0, 0.8, 1.2), p.num(2.0, 1.6, 2.4), p.num(3.0, 2.6, 3.4);
  const double G = p.num(0.5, 0.3, 0.7);
  double scale = 0;

  // eps = 0: G m_0 m_2 / 125 = 1.5 / 125, G m_1 m_2 / 125 = 3 / 125:
  // (0.036, 0.048), (0.072, 0.096) and (-0.108, -0.144).
  Mat2X f = Mat2X::Zero(2, 3);
  add_newton_gravity(x, m, G, 0.0, f);
  wbtest::require_finite(f, "unsoftened gravity with two coincident bodies");
  wbtest::require_near(f, newton_law(x, m, G, 0.0, Mat2X::Zero(2, 3), scale), kTol,
                       "eps = 0: a coincident pair adds nothing, the others still attract", kTol);

  // eps = sqrt(11): r^2 + eps^2 = 36, 36^(3/2) = 216: 1.5 (3, 4) / 216 and 3 (3, 4) / 216.
  const double eps = std::sqrt(p.num(11.0, 8.0, 14.0));
  f.setZero();
  add_newton_gravity(x, m, G, eps, f);
  wbtest::require_finite(f, "softened gravity with two coincident bodies");
  wbtest::require_near(f, newton_law(x, m, G, eps, Mat2X::Zero(2, 3), scale), kTol,
                       "eps > 0: a coincident pair has d = 0 so adds nothing, the others attract",
                       kTol);
}

// The held-out test's own case (no public test makes it): a cluster of 3 to 20 bodies as the
// public cluster draws them (points from a drawn seed, in a drawn range), two of them at the
// same place (a coincident pair adds nothing, with or without softening), G, eps (0 or
// drawn) and the forces already there short decimals. Up to 20 bodies, so that the public
// cluster's 12 lies inside the held-out calls' sizes, not at their top.
void random_cluster(const wbtest::Params& p, bool soft) {
  const Eigen::Index n = p.count(8, 3, 20);
  const double s = p.num(1.0, 0.5, 3.0);
  Mat2X x = wbtest::random_points(n, std::uint64_t(p.count(1, 1, 1000000)), -s, s);
  const Eigen::Index a = p.count(0, 0, n - 1), b = (a + p.count(1, 1, n - 1)) % n;
  x.col(b) = x.col(a);
  const VecX m = wbtest::random_points(n, std::uint64_t(p.count(2, 1, 1000000)), 0.5, 2.0)
                     .row(0)
                     .transpose();
  const double G = p.num(1.0, 0.3, 2.0), eps = soft ? p.num(0.1, 0.03, 0.5) : 0.0;
  Mat2X f0(2, n);
  for (Eigen::Index i = 0; i < n; ++i) f0.col(i) = Vec2(p.num(0, -2.0, 2.0), p.num(0, -2.0, 2.0));
  Mat2X f = f0;
  add_newton_gravity(x, m, G, eps, f);
  double scale = 0;
  const Mat2X expected = newton_law(x, m, G, eps, f0, scale);
  INFO("x = " << x << "\n  m = " << m.transpose() << ", G = " << G << ", eps = " << eps
              << " (bodies " << a << " and " << b << " coincide)");
  wbtest::require_near(f, expected, 1e-12 * (1.0 + scale),
                       "each body gets sum_{j != i} G m_i m_j (x_j - x_i) / "
                       "(r^2 + eps^2)^(3/2), added to f",
                       1e-12);
}

}  // namespace

TEST_CASE("F2 newton gravity: two bodies attract with G m_i m_j d / r^3", "[forces][F2][3pts]") {
  two_bodies(wbtest::Params());
}

TEST_CASE("F2 newton gravity: softening replaces r^2 by r^2 + eps^2", "[forces][F2][2pts]") {
  softening(wbtest::Params());
}

TEST_CASE("F2 newton gravity: adds to the forces already there", "[forces][F2][1pts]") {
  adds_up(wbtest::Params());
}

TEST_CASE("F2 newton gravity: pair forces cancel so a cluster keeps its momentum",
          "[forces][F2][2pts]") {
  cluster(wbtest::Params());
}

TEST_CASE("F2 newton gravity: the force is minus the gradient of the softened potential",
          "[forces][F2][2pts]") {
  minus_gradient(wbtest::Params());
}

TEST_CASE("F2 newton gravity: coincident bodies give finite forces with and without softening",
          "[forces][F2][2pts]") {
  coincident(wbtest::Params());
}

// Every public scenario above again, its parameters drawn from the held-out seed in the public
// tests' format, and two clusters of its own in the same format, so that no call tells the
// public tests from this one (tools/adversary --inputs).
TEST_CASE("F2 held-out: random clusters attract pairwise with G m_i m_j d / (r^2 + eps^2)^(3/2)",
          "[forces][F2][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F2")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    two_bodies(p);
    softening(p);
    adds_up(p);
    cluster(p);
    minus_gradient(p);
    coincident(p);
    random_cluster(p, false);
    random_cluster(p, true);
  }
}

}  // namespace test_F2_newton_gravity
