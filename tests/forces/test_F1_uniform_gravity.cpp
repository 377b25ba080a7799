// F1 uniform gravity: f_i += m_i g (labs/forces/uniform_gravity.h).
#include "heldout.h"
#include "params.h"
#include "test_helpers.h"
#include "uniform_gravity.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F1_uniform_gravity {

using wb::Mat2X;
using wb::Vec2;
using wb::VecX;

namespace {
// Sums of a few products of short decimals: rounding only.
constexpr double kTol = 1e-12;

// The scenarios of the public tests below, each a function of its parameters: the public test
// runs it with the published ones (wbtest::Params()), the held-out test with drawn ones, in the
// same format (tests/common/params.h): short decimals, 2 to 4 particles, about the published
// magnitudes.

// Distinct masses (one below 1, so m^2 != m) and a g with both components non-zero and
// different, so a missing or squared mass or swapped x/y shows. Held-out: 3 particles (2 to 4
// would make 4 particle calls, which no public test makes), the masses in three disjoint
// ranges (one below 1), g with |g_y| > 5 > |g_x|.
void each_particle(const wbtest::Params& p) {
  VecX m(3);
  m << p.num(0.5, 0.2, 0.9), p.num(2.0, 1.2, 2.8), p.num(3.0, 2.2, 4.0);
  const Vec2 g(p.num(1.5, 0.5, 2.5), p.num(-9.81, -12.0, -5.0));
  Mat2X f = Mat2X::Zero(2, 3);
  add_uniform_gravity(m, g, f);
  // m_i g; published: (0.75, -4.905), (3, -19.62), (4.5, -29.43)
  const Mat2X expected = g * m.transpose();
  wbtest::require_near(f, expected, kTol, "uniform gravity: f_i = m_i g (weight is mass times g)",
                       kTol);
  INFO("f keeps one column per particle (3); got " << f.cols()
                                                   << ": add into f, never resize it");
  REQUIRE(f.cols() == 3);
}

// Held-out: 2 particles, the masses (one below 1), g and the forces already there drawn about
// the published ones.
void adds_up(const wbtest::Params& p) {
  VecX m(2);
  m << p.num(0.25, 0.1, 0.9), p.num(4.0, 1.5, 5.0);
  const Vec2 g(p.num(-2.0, -3.0, -0.5), p.num(8.0, 5.0, 11.0));
  Mat2X f(2, 2);
  f << p.num(10.0, 6.0, 14.0), p.num(-3.0, -6.0, -1.0),  //
      p.num(7.0, 3.0, 9.0), p.num(0.5, 0.1, 2.0);
  const Mat2X f0 = f;
  add_uniform_gravity(m, g, f);
  // previous + m_i g; published: (10 - 0.5, 7 + 2) and (-3 - 8, 0.5 + 32)
  const Mat2X expected = f0 + g * m.transpose();
  wbtest::require_near(f, expected, kTol,
                       "forces add up (superposition): f must keep what other terms put there",
                       kTol);
}

// Held-out: 3 particles, the masses, g and the points drawn (the points from a drawn seed, in
// the published range).
void minus_gradient(const wbtest::Params& p) {
  VecX m(3);
  m << p.num(1.5, 1.0, 2.0), p.num(0.2, 0.1, 0.6), p.num(2.5, 2.1, 3.0);
  const Vec2 g(p.num(0.3, -1.0, 1.0), p.num(-9.81, -12.0, -5.0));
  const Mat2X x = wbtest::random_points(3, std::uint64_t(p.count(11, 1, 1000000)), -2.0, 2.0);
  auto V = [&](const Mat2X& y) { return -(g.transpose() * y).dot(m); };
  // V is linear in x, so central differences are exact up to rounding:
  // about eps_mach |V| / h = 1e-16 * 100 / 1e-3, far under the tolerance.
  const double h = 1e-3, tol = 1e-9;
  const Mat2X expected = wbtest::minus_gradient(V, x, h);
  Mat2X f = Mat2X::Zero(2, 3);
  add_uniform_gravity(m, g, f);
  wbtest::require_near(f, expected, tol, "gravity is conservative: f = -dV/dx", tol);
}

// The held-out test's own case (no public test makes it): 2 to 3 particles, each mass, g and
// the forces already there drawn, in the public tests' ranges and format.
void random_particles(const wbtest::Params& p) {
  const Eigen::Index n = p.count(3, 2, 3);
  VecX m(n);
  Mat2X f0(2, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    m[i] = p.num(1.0, 0.1, 4.0);
    f0.col(i) = Vec2(p.num(0.0, -10.0, 10.0), p.num(0.0, -10.0, 10.0));
  }
  const Vec2 grav(p.num(0.0, -3.0, 3.0), p.num(-9.81, -12.0, -5.0));
  Mat2X f = f0;
  add_uniform_gravity(m, grav, f);
  Mat2X expected = f0;
  for (Eigen::Index i = 0; i < n; ++i) expected.col(i) += m[i] * grav;
  INFO("m = " << m.transpose() << ", g = " << wbtest::str(grav) << ", f before = " << f0);
  wbtest::require_near(f, expected, kTol, "uniform gravity: f_i += m_i g", kTol);
}

}  // namespace

TEST_CASE("F1 uniform gravity: each particle gets m_i g", "[forces][F1][2pts]") {
  each_particle(wbtest::Params());
}

TEST_CASE("F1 uniform gravity: adds to the forces already there", "[forces][F1][2pts]") {
  adds_up(wbtest::Params());
}

TEST_CASE("F1 uniform gravity: the force is minus the gradient of V = -sum m_i g . x_i",
          "[forces][F1][2pts]") {
  minus_gradient(wbtest::Params());
}

// Every public scenario above again, its parameters drawn from the held-out seed in the public
// tests' format, and a case of its own in the same format, so that no call tells the public
// tests from this one (tools/adversary --inputs).
TEST_CASE("F1 held-out: random particles get f_i += m_i g", "[forces][F1][held-out][1pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F1")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    each_particle(p);
    adds_up(p);
    minus_gradient(p);
    random_particles(p);
  }
}

}  // namespace test_F1_uniform_gravity
