// F4 viscous damping: f_i += -b v_i (labs/forces/damping.h).
#include "damping.h"
#include "heldout.h"
#include "params.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F4_damping {

using wb::Mat2X;
using wb::Vec2;

namespace {
// Products of short decimals: rounding only.
constexpr double kTol = 1e-12;

// The scenarios of the public tests below, each a function of its parameters: the public test
// runs it with the published ones (wbtest::Params()), the held-out test with drawn ones, in the
// same format (tests/common/params.h): short decimals, the published particle counts, about
// the published magnitudes.

// Held-out: b and the first two velocities drawn about the published ones; the third stays
// exactly 0 (no force on a particle at rest).
void opposes_velocity(const wbtest::Params& p) {
  const double b = p.num(0.7, 0.3, 1.2);
  Mat2X v(2, 3);
  v << p.num(3.0, 2.0, 4.0), p.num(-0.5, -1.5, -0.2), 0.0,  //
      p.num(-4.0, -5.0, -3.0), p.num(2.0, 1.0, 3.0), 0.0;
  Mat2X f = Mat2X::Zero(2, 3);
  add_damping(v, b, f);
  // published (b = 0.7): (-2.1, 2.8), (0.35, -1.4), and no force on the particle at rest
  const Mat2X expected = -b * v;
  wbtest::require_near(f, expected, kTol, "viscous drag: f = -b v, against the motion", kTol);
}

// Held-out: b, the velocities (one component exactly 0, as published) and the forces already
// there drawn about the published ones.
void adds_up(const wbtest::Params& p) {
  const double b = p.num(0.5, 0.2, 0.9);
  Mat2X v(2, 2);
  v << p.num(1.0, 0.5, 2.0), 0.0,  //
      p.num(2.0, 1.0, 3.0), p.num(-3.0, -4.0, -2.0);
  Mat2X f(2, 2);
  f << p.num(5.0, 3.0, 7.0), p.num(-1.0, -2.0, -0.5),  //
      p.num(6.0, 4.0, 8.0), p.num(0.25, 0.1, 1.0);
  const Mat2X f0 = f;
  add_damping(v, b, f);
  // previous - b v; published: (5 - 0.5, 6 - 1) and (-1 - 0, 0.25 + 1.5)
  wbtest::require_near(f, Mat2X(f0 - b * v), kTol,
                       "forces add up (superposition): f must keep what other terms put there",
                       kTol);
}

// Power of the drag on each particle: f . v = -b |v|^2 <= 0 (it only dissipates).
// Held-out: b and the velocities' seed drawn (5 velocities in the published range).
void dissipates(const wbtest::Params& p) {
  const Mat2X v = wbtest::random_points(5, std::uint64_t(p.count(99, 1, 1000000)), -2.0, 2.0);
  const double b = p.num(1.25, 0.8, 1.8);
  // Other terms' forces already there (as in a step), so the drag is f - f0: a step that
  // overwrote f instead of adding to it fails here too, not only where f0 is a short decimal.
  const Mat2X f0 = wbtest::random_points(5, std::uint64_t(p.count(98, 1, 1000000)), -2.0, 2.0);
  Mat2X f = f0;
  add_damping(v, b, f);
  for (Eigen::Index i = 0; i < 5; ++i) {
    CAPTURE(i);
    const Vec2 vi = v.col(i);
    wbtest::require_near(
        Vec2(f.col(i) - f0.col(i)).dot(vi), -b * vi.squaredNorm(), kTol,
        "power of viscous drag: (f - f0) . v = -b |v|^2, f0 the forces already there", kTol);
  }
}

// The held-out test's own case (no public test makes it): 2 to 5 particles, b, every velocity
// and force already there drawn, as short decimals of a drawn magnitude.
void random_velocities(const wbtest::Params& p) {
  const Eigen::Index n = p.count(3, 2, 5);
  const double a = p.num(4.0, 1.0, 8.0), b = p.num(0.7, 0.1, 2.0);
  Mat2X v(2, n), f0(2, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int d = 0; d < 2; ++d) {
      v(d, i) = p.num(0.0, -a, a);
      f0(d, i) = p.num(0.0, -a, a);
    }
  }
  Mat2X f = f0;
  add_damping(v, b, f);
  INFO("b = " << b << ", v = " << v << "\n  f before = " << f0);
  wbtest::require_near(f, Mat2X(f0 - b * v), kTol, "viscous drag f_i += -b v_i", kTol);
}

}  // namespace

TEST_CASE("F4 damping: f = -b v opposes the velocity with magnitude b |v|",
          "[forces][F4][2pts]") {
  // b = 0.7. v_0 = (3, -4): f_0 = (-2.1, 2.8), |f_0| = 0.7 * 5 = 3.5.
  // v_1 = (-0.5, 2):  f_1 = (0.35, -1.4). v_2 = 0: no force.
  // (The drag does not involve the mass: the same b for every particle.)
  opposes_velocity(wbtest::Params());
}

TEST_CASE("F4 damping: adds to the forces already there", "[forces][F4][2pts]") {
  adds_up(wbtest::Params());
}

TEST_CASE("F4 damping: the drag removes energy at the rate b |v|^2", "[forces][F4][1pts]") {
  dissipates(wbtest::Params());
}

// Every public scenario above again, its parameters drawn from the held-out seed in the public
// tests' format, and a case of its own in the same format, so that no call tells the public
// tests from this one (tools/adversary --inputs).
TEST_CASE("F4 held-out: random velocities get f_i += -b v_i", "[forces][F4][held-out][1pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F4")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    opposes_velocity(p);
    adds_up(p);
    dissipates(p);
    random_velocities(p);
  }
}

}  // namespace test_F4_damping
