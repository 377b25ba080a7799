// F7 boids: steering as a proxy force f_i += m_i s_i (labs/forces/boids.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>

#include "boids.h"
#include "heldout.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F7_boids {

using wb::Mat2X;
using wb::Vec2;
using wb::VecX;

namespace {

// Hand-derived values below are short decimals or thirds: rounding only.
constexpr double kTol = 1e-12;

Mat2X cols(std::initializer_list<Vec2> list) {
  Mat2X out(2, Eigen::Index(list.size()));
  Eigen::Index i = 0;
  for (const Vec2& c : list) out.col(i++) = c;
  return out;
}

VecX masses(std::initializer_list<double> list) {
  VecX out(Eigen::Index(list.size()));
  Eigen::Index i = 0;
  for (double c : list) out[i++] = c;
  return out;
}

// Mean of the columns `idx` of a (idx non-empty).
Vec2 mean_of(const Mat2X& a, std::initializer_list<Eigen::Index> idx) {
  Vec2 s = Vec2::Zero();
  for (Eigen::Index j : idx) s += a.col(j);
  return s / double(idx.size());
}

}  // namespace

TEST_CASE("F7 boids: a lone boid is pulled to its goal with magnitude m w_g",
          "[forces][F7][2pts]") {
  // Boid at (1, 2), goal (4, 6): goal - x = (3, 4), distance 5, unit (0.6, 0.8).
  // w_g = 0.5, m = 2: f = 2 * 0.5 (0.6, 0.8) = (0.6, 0.8), magnitude m w_g = 1
  // whatever the distance. All the rules are on, but a lone boid has no
  // neighbours: the means over empty sets count as 0.
  BoidsParams p;
  p.separation = {0.2, 1.0};
  p.alignment = {0.5, 1.0};
  p.cohesion = {0.3, 1.0};
  p.goal = Vec2(4, 6);
  p.goal_weight = 0.5;
  const Mat2X x = cols({Vec2(1, 2)}), v = cols({Vec2(0.7, -0.2)});
  const VecX m = masses({2.0});
  Mat2X f = Mat2X::Zero(2, 1);
  add_boids(x, v, m, p, f);
  wbtest::require_finite(f, "a lone boid (no neighbours for the means)");
  wbtest::require_near(Vec2(f.col(0)), Vec2(0.6, 0.8), kTol,
                       "goal steering: f = m w_g (goal - x) / |goal - x|, a unit direction",
                       kTol);

  // Added to what is already there.
  f << 1.0, -1.0;
  add_boids(x, v, m, p, f);
  wbtest::require_near(Vec2(f.col(0)), Vec2(1.6, -0.2), kTol,
                       "forces add up (superposition): f must keep what other terms put there",
                       kTol);
}

TEST_CASE("F7 boids: two close boids push apart with w_s m d / r^2", "[forces][F7][2pts]") {
  // x_0 = (1, 1), x_1 = (1.3, 1.4): x_0 - x_1 = (-0.3, -0.4), r = 0.5, r^2 = 0.25,
  // (x_0 - x_1) / r^2 = (-1.2, -1.6). w_s = 0.2, radius 1, m = (2, 3):
  //   f_0 = 2 * 0.2 (-1.2, -1.6) = (-0.48, -0.64)  (magnitude w_s m / r = 0.8)
  //   f_1 = 3 * 0.2 ( 1.2,  1.6) = ( 0.72,  0.96)
  BoidsParams p;
  p.separation = {0.2, 1.0};
  const Mat2X x = cols({Vec2(1, 1), Vec2(1.3, 1.4)});
  const Mat2X v = cols({Vec2(1, 0), Vec2(0, 1)});
  const VecX m = masses({2.0, 3.0});
  Mat2X f = Mat2X::Zero(2, 2);
  add_boids(x, v, m, p, f);
  {
    INFO("separation must push boid 0 away from boid 1: f_0 . (x_1 - x_0) < 0, got f_0 = "
         << wbtest::str(f.col(0)));
    REQUIRE(wbtest::finite(Vec2(f.col(0)).dot(x.col(1) - x.col(0))) < 0);
  }
  wbtest::require_near(Vec2(f.col(0)), Vec2(-0.48, -0.64), kTol,
                       "separation: w_s m_0 (x_0 - x_1) / |x_0 - x_1|^2", kTol);
  wbtest::require_near(Vec2(f.col(1)), Vec2(0.72, 0.96), kTol,
                       "separation: w_s m_1 (x_1 - x_0) / |x_1 - x_0|^2", kTol);
}

TEST_CASE("F7 boids: alignment steers to the neighbours' mean velocity", "[forces][F7][3pts]") {
  // Four boids, all within the alignment radius of each other, w_a = 0.5,
  // m = (1, 2, 0.5, 4). v = (1, 0), (0, 2), (-1, 1), (2, -1).
  //   i = 0: mean of v_1 v_2 v_3 = (1/3, 2/3), minus v_0 = (-2/3, 2/3),  f = 1 * 0.5 * that =
  //   (-1/3, 1/3) i = 1: mean of v_0 v_2 v_3 = (2/3, 0),   minus v_1 = (2/3, -2),    f = 2 * 0.5
  //   * that = (2/3, -2) i = 2: mean of v_0 v_1 v_3 = (1, 1/3),   minus v_2 = (2, -2/3),    f =
  //   0.5 * 0.5 * that = (0.5, -1/6) i = 3: mean of v_0 v_1 v_2 = (0, 1),     minus v_3 = (-2,
  //   2),      f = 4 * 0.5 * that = (-4, 4)
  // (The mean is over the others: including the boid itself would give 3/4 of these.)
  BoidsParams p;
  p.alignment = {0.5, 2.0};
  const Mat2X x = cols({Vec2(0, 0), Vec2(0.5, 0.2), Vec2(0.1, 0.6), Vec2(0.4, 0.7)});
  const Mat2X v = cols({Vec2(1, 0), Vec2(0, 2), Vec2(-1, 1), Vec2(2, -1)});
  const VecX m = masses({1.0, 2.0, 0.5, 4.0});
  Mat2X f = Mat2X::Zero(2, 4);
  add_boids(x, v, m, p, f);
  const Mat2X expected =
      cols({Vec2(-1.0 / 3, 1.0 / 3), Vec2(2.0 / 3, -2), Vec2(0.5, -1.0 / 6), Vec2(-4, 4)});
  wbtest::require_near(
      f, expected, kTol,
      "alignment: w_a m_i (mean of the neighbours' v_j - v_i), neighbours j != i", kTol);
}

TEST_CASE("F7 boids: cohesion steers to the neighbours' centre", "[forces][F7][2pts]") {
  // Three boids within the cohesion radius, w_c = 0.3, m = (2, 1, 0.5).
  // x = (0.2, 0.1), (1.4, 0.7), (0.5, 1.6).
  //   i = 0: mean of x_1 x_2 = (0.95, 1.15), minus x_0 = (0.75, 1.05),  f = 2 * 0.3 * that   =
  //   (0.45, 0.63) i = 1: mean of x_0 x_2 = (0.35, 0.85), minus x_1 = (-1.05, 0.15), f = 1 * 0.3
  //   * that   = (-0.315, 0.045) i = 2: mean of x_0 x_1 = (0.8, 0.4),   minus x_2 = (0.3, -1.2),
  //   f = 0.5 * 0.3 * that = (0.045, -0.18)
  BoidsParams p;
  p.cohesion = {0.3, 3.0};
  const Mat2X x = cols({Vec2(0.2, 0.1), Vec2(1.4, 0.7), Vec2(0.5, 1.6)});
  const Mat2X v = cols({Vec2(1, 0), Vec2(0, 1), Vec2(-1, -1)});
  const VecX m = masses({2.0, 1.0, 0.5});
  Mat2X f = Mat2X::Zero(2, 3);
  add_boids(x, v, m, p, f);
  const Mat2X expected = cols({Vec2(0.45, 0.63), Vec2(-0.315, 0.045), Vec2(0.045, -0.18)});
  wbtest::require_near(f, expected, kTol,
                       "cohesion: w_c m_i (mean of the neighbours' x_j - x_i), neighbours j != i",
                       kTol);
}

TEST_CASE("F7 boids: each rule sees only the neighbours inside its own radius",
          "[forces][F7][2pts]") {
  // Radii: separation 0.6, alignment 1.2, cohesion 2.0. Five boids:
  //   0 (0, 0), 1 (0.3, 0.4), 2 (0.8, -0.6), 3 (-0.9, 1.2), 4 (10, 10).
  // Distances: 01 = 0.5, 02 = 1.0, 03 = 1.5, 12 = 1.118, 13 = 1.442, 23 = 2.476,
  // boid 4 is more than 10 from all (none is near a radius: margins >= 0.08).
  // Neighbour sets (separation / alignment / cohesion):
  //   0: {1} / {1, 2} / {1, 2, 3}     1: {0} / {0, 2} / {0, 2, 3}
  //   2: {}  / {0, 1} / {0, 1}        3: {}  / {}     / {0, 1}       4: none
  BoidsParams p;
  p.separation = {0.1, 0.6};
  p.alignment = {0.5, 1.2};
  p.cohesion = {0.3, 2.0};
  const Mat2X x =
      cols({Vec2(0, 0), Vec2(0.3, 0.4), Vec2(0.8, -0.6), Vec2(-0.9, 1.2), Vec2(10, 10)});
  const Mat2X v = cols({Vec2(1, 0), Vec2(0, 2), Vec2(-1, 1), Vec2(2, -1), Vec2(3, 3)});
  const VecX m = masses({1.0, 2.0, 0.5, 4.0, 1.5});
  Mat2X f = Mat2X::Zero(2, 5);
  add_boids(x, v, m, p, f);

  // The header's terms over the sets above.
  const double ws = 0.1, wa = 0.5, wc = 0.3;
  Mat2X expected(2, 5);
  const Vec2 x0 = x.col(0), x1 = x.col(1), x2 = x.col(2), x3 = x.col(3);
  const Vec2 v0 = v.col(0), v1 = v.col(1), v2 = v.col(2);
  expected.col(0) = m[0] * (ws * (x0 - x1) / 0.25 + wa * (mean_of(v, {1, 2}) - v0) +
                            wc * (mean_of(x, {1, 2, 3}) - x0));
  expected.col(1) = m[1] * (ws * (x1 - x0) / 0.25 + wa * (mean_of(v, {0, 2}) - v1) +
                            wc * (mean_of(x, {0, 2, 3}) - x1));
  expected.col(2) = m[2] * (wa * (mean_of(v, {0, 1}) - v2) + wc * (mean_of(x, {0, 1}) - x2));
  expected.col(3) = m[3] * (wc * (mean_of(x, {0, 1}) - x3));
  expected.col(4) = Vec2::Zero();
  wbtest::require_finite(f, "boids with some empty neighbour sets");
  wbtest::require_near(f, expected, kTol,
                       "neighbours are the boids with 0 < |x_j - x_i| < radius of that rule: "
                       "the means are over them only",
                       kTol);
}

TEST_CASE("F7 boids: coincident boids and a boid at its goal give no NaN", "[forces][F7][2pts]") {
  // Boids 0 and 1 both at (1, 1); boid 2 at (1.3, 1.4), 0.5 away, and on the goal.
  // Every rule has radius 1; w_s = 0.2, w_a = 0.5, w_c = 0.3, w_g = 0.5; m = (1, 2, 0.5);
  // v = (1, 0), (0, 1), (-1, -1). The coincident pair are not neighbours
  // (0 < |x_j - x_i| fails), so boids 0 and 1 each see only boid 2:
  //   sep (-0.3, -0.4) / 0.25 * 0.2 = (-0.24, -0.32), coh (0.3, 0.4) * 0.3 = (0.09, 0.12),
  //   goal 0.5 (0.6, 0.8) = (0.3, 0.4); align 0.5 (v_2 - v_i):
  //   s_0 = ... + (-1, -0.5) = (-0.85, -0.3),  f_0 = 1 * s_0
  //   s_1 = ... + (-0.5, -1) = (-0.35, -0.8),  f_1 = 2 * s_1 = (-0.7, -1.6)
  // Boid 2 sees both, at (1, 1), and sits on its goal (no goal term):
  //   sep 2 (0.3, 0.4) / 0.25 * 0.2 = (0.48, 0.64), align 0.5 ((0.5, 0.5) - (-1, -1)) = (0.75,
  //   0.75), coh 0.3 ((1, 1) - (1.3, 1.4)) = (-0.09, -0.12): s_2 = (1.14, 1.27), f_2 = 0.5 s_2 =
  //   (0.57, 0.635)
  BoidsParams p;
  p.separation = {0.2, 1.0};
  p.alignment = {0.5, 1.0};
  p.cohesion = {0.3, 1.0};
  p.goal = Vec2(1.3, 1.4);
  p.goal_weight = 0.5;
  const Mat2X x = cols({Vec2(1, 1), Vec2(1, 1), Vec2(1.3, 1.4)});
  const Mat2X v = cols({Vec2(1, 0), Vec2(0, 1), Vec2(-1, -1)});
  const VecX m = masses({1.0, 2.0, 0.5});
  Mat2X f = Mat2X::Zero(2, 3);
  add_boids(x, v, m, p, f);
  wbtest::require_finite(f, "boids with two coincident boids and one at its goal");
  const Mat2X expected = cols({Vec2(-0.85, -0.3), Vec2(-0.7, -1.6), Vec2(0.57, 0.635)});
  wbtest::require_near(f, expected, kTol,
                       "coincident boids are not neighbours of each other, and a boid at the "
                       "goal has no goal term",
                       kTol);
}

TEST_CASE(
    "F7 boids: a flock with only alignment converges to its mean velocity at the predicted rate",
    "[forces][F7][2pts]") {
  // When every boid is a neighbour of every other (n boids, huge radius), the
  // acceleration is a_i = s_i = w_a (mean_{j != i} v_j - v_i) = w_a n/(n-1) (vbar - v_i),
  // whatever the masses. With semi-implicit Euler (v += h a; x += h v) the mean
  // vbar does not change and each deviation v_i - vbar is multiplied by exactly
  // q = 1 - h w_a n/(n-1) per step (n = 2: the relative velocity v_0 - v_1 decays
  // by 1 - 2 h w_a, the discrete form of exp(-2 w_a t)). After N steps the
  // deviation is q^N times the initial one; 100 steps of rounding leave < 1e-12.
  const double wa = 0.8, h = 0.01;
  const int steps = 100;
  BoidsParams p;
  p.alignment = {wa, 1e3};  // the flock stays within a few metres: everyone is a neighbour

  for (Eigen::Index n : {Eigen::Index(2), Eigen::Index(5)}) {
    CAPTURE(n);
    Mat2X x = wbtest::random_points(n, 31, -1.0, 1.0);
    Mat2X v = wbtest::random_points(n, 32, -2.0, 2.0);
    const VecX m = wbtest::random_points(n, 33, 0.5, 3.0).row(0).transpose();
    const Vec2 vbar = v.rowwise().mean();
    const Mat2X dev0 = v.colwise() - vbar;
    Mat2X f(2, n);
    for (int k = 0; k < steps; ++k) {
      f.setZero();
      add_boids(x, v, m, p, f);
      for (Eigen::Index i = 0; i < n; ++i) v.col(i) += h * f.col(i) / m[i];
      x += h * v;
    }
    const double q = 1.0 - h * wa * double(n) / double(n - 1);
    const Mat2X expected = std::pow(q, steps) * dev0;
    const Mat2X dev = v.colwise() - vbar;
    wbtest::require_near(dev, expected, 1e-12,
                         "alignment only: velocity deviations from the mean shrink by "
                         "1 - h w_a n/(n-1) per semi-implicit Euler step",
                         1e-10);
  }
}

TEST_CASE("F7 held-out: random flocks get the four rules of the header",
          "[forces][F7][held-out][3pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F7")) {
    INFO(g.replay());
    const Eigen::Index n = g.integer(9, 13);
    // Boids in a box about as wide as the radii, so that each has some neighbours and not
    // others; two at the same place (never neighbours), one at the goal, and the last one
    // close to another (so that it always feels something).
    Mat2X x = g.points(n, -1.5, 1.5);
    const Mat2X v = g.points(n, -2.0, 2.0);
    const VecX m = g.values(n, 0.2, 3.0);
    x.col(1) = x.col(0);
    x.col(n - 1) = x.col(3) + g.uniform(0.1, 0.35) * g.unit2();  // the last has neighbours
    x.col(n - 2) = g.vec2(40, 60);  // a lone boid: no neighbours at all, means over empty sets
    BoidsParams p;
    p.separation = {g.uniform(0.05, 1.0), g.uniform(0.4, 1.2)};
    p.alignment = {g.uniform(0.05, 1.0), g.uniform(0.8, 2.0)};
    p.cohesion = {g.uniform(0.05, 1.0), g.uniform(1.2, 3.0)};
    p.goal_weight = g.uniform(0.1, 2.0);
    p.goal = x.col(2);
    // Boid 4's neighbours 5 and 6 between the radii: 5 within the middle radius and not the
    // smallest, 6 within the largest and not the middle one (each rule its own radius).
    std::array<double, 3> radii = {p.separation.radius, p.alignment.radius, p.cohesion.radius};
    std::sort(radii.begin(), radii.end());
    x.col(5) = x.col(4) + g.uniform(radii[0] + 0.05 * (radii[1] - radii[0]),
                                    radii[1] - 0.05 * (radii[1] - radii[0])) *
                              g.unit2();
    x.col(6) = x.col(4) + g.uniform(radii[1] + 0.05 * (radii[2] - radii[1]),
                                    radii[2] - 0.05 * (radii[2] - radii[1])) *
                              g.unit2();
    const Mat2X f0 = g.points(n, -3.0, 3.0);
    Mat2X f = f0;
    add_boids(x, v, m, p, f);
    Mat2X expected = f0;
    double scale = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      Vec2 sep(0, 0), vsum(0, 0), xsum(0, 0);
      int na = 0, nc = 0;
      for (Eigen::Index j = 0; j < n; ++j) {
        const Vec2 d = x.col(i) - x.col(j);
        const double r = d.norm();
        if (j == i || r == 0) continue;
        if (r < p.separation.radius) sep += d / (r * r);
        if (r < p.alignment.radius) vsum += v.col(j), ++na;
        if (r < p.cohesion.radius) xsum += x.col(j), ++nc;
      }
      Vec2 s = p.separation.weight * sep;
      if (na > 0) s += p.alignment.weight * (vsum / na - v.col(i));
      if (nc > 0) s += p.cohesion.weight * (xsum / nc - x.col(i));
      const Vec2 to_goal = p.goal - x.col(i);
      if (to_goal.norm() > 0) s += p.goal_weight * to_goal / to_goal.norm();
      expected.col(i) += m[i] * s;
      scale += m[i] * s.norm();
    }
    INFO("x = " << x << "\n  v = " << v << "\n  m = " << m.transpose() << "\n  separation "
                << p.separation.weight << " within " << p.separation.radius << ", alignment "
                << p.alignment.weight << " within " << p.alignment.radius << ", cohesion "
                << p.cohesion.weight << " within " << p.cohesion.radius << ", goal "
                << p.goal_weight << " at " << wbtest::str(p.goal));
    wbtest::require_near(f, expected, 1e-11 * (1.0 + scale),
                         "f_i += m_i (separation + alignment + cohesion + goal), each rule over "
                         "its own neighbours j != i with 0 < |x_j - x_i| < its radius",
                         1e-11);
  }
}

}  // namespace test_F7_boids
