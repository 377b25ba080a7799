// F9 curl noise: psi ramped at obstacles, the flow u = curl psi by central
// differences, and the drag f_i += b (u(x_i) - v_i) (labs/forces/curl_noise.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "curl_noise.h"
#include "heldout.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_F9_curl_noise {

using wb::Mat2X;
using wb::Vec2;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The divergence of a central-difference curl, measured with the same step h,
// cancels exactly in exact arithmetic (both terms combine the same four values
// psi(x +- h e_x +- h e_y)); what remains is the rounding of the u values,
// about eps |u| / h. Allowed: 1000 times that. A wrong curl leaves ~|grad u|.
constexpr double kDivRoundoffFactor = 1000.0;
// Central differences of a smooth psi with h = 1e-5: truncation h^2/6 |psi'''|
// ~ 1e-10 and rounding eps |psi| / h ~ 1e-10 for the fields below.
constexpr double kFlowTol = 1e-7;
// Hand-derived values below are short decimals or exact binary fractions.
constexpr double kTol = 1e-12;

// The flow of the scene tests: noise of amplitude 1.5 m/s and scale 2 m, plus a wind.
CurlNoiseParams noise_field(std::uint64_t seed = 7) {
  CurlNoiseParams p;
  p.psi = wb::noise_potential(seed, 1.5, 2.0, Vec2(0.3, -0.2));
  p.b = 1.0;
  p.h = 1e-4;
  return p;
}

// The discrete divergence of the student's flow at x, by central differences
// with the flow's own step h.
double divergence(const Vec2& x, const CurlNoiseParams& p) {
  const Vec2 ex(p.h, 0), ey(0, p.h);
  return (curl_noise_flow(x + ex, p).x() - curl_noise_flow(x - ex, p).x()) / (2 * p.h) +
         (curl_noise_flow(x + ey, p).y() - curl_noise_flow(x - ey, p).y()) / (2 * p.h);
}

// The Rankine vortex of F8 (centre (1, -1), omega = 2, core R = 2) as a stream
// function: psi = -omega r^2 / 2 inside, -omega R^2 (ln(r / R) + 1/2) outside
// (continuous, with continuous slope, at r = R). Its curl (dpsi/dy, -dpsi/dx)
// is omega perp(d) inside and omega R^2 perp(d) / r^2 outside.
double rankine_psi(const Vec2& x) {
  const Vec2 d = x - Vec2(1, -1);
  const double omega = 2.0, R = 2.0, r = d.norm();
  if (r <= R) return -omega * r * r / 2;
  return -omega * R * R * (std::log(r / R) + 0.5);
}

// The ramp of the header at s = 1/4 and 1/2, exactly:
// 15/8 s - 10/8 s^3 + 3/8 s^5.
constexpr double kRampQuarter = 15.0 / 32 - 10.0 / 512 + 3.0 / 8192;  // 0.4495849609375
constexpr double kRampHalf = 15.0 / 16 - 10.0 / 64 + 3.0 / 256;       // 0.79296875

}  // namespace

TEST_CASE("F9 curl noise: the flow is divergence-free to the rounding of the differences",
          "[forces][F9][1pts]") {
  CurlNoiseParams p = noise_field();
  const Mat2X pts = wbtest::random_points(40, 91, -5.0, 5.0);
  for (int with_obstacles = 0; with_obstacles < 2; ++with_obstacles) {
    if (with_obstacles) {
      p.obstacles = {{Vec2(0.5, 0.5), 1.0}, {Vec2(-2.5, 1.0), 0.7}};
      p.ramp = 1.2;
    }
    double u_max = 0, div_max = 0, vort_max = 0;
    for (Eigen::Index i = 0; i < pts.cols(); ++i) {
      const Vec2 x = pts.col(i);
      const Vec2 u = curl_noise_flow(x, p);
      u_max = wbtest::worst_of(u_max, u.norm());
      div_max = wbtest::worst_of(div_max, std::abs(divergence(x, p)));
      // The vorticity scale (the size of grad u that a wrong curl leaves as divergence).
      const Vec2 ex(p.h, 0), ey(0, p.h);
      const double w = (curl_noise_flow(x + ex, p).y() - curl_noise_flow(x - ex, p).y() -
                        curl_noise_flow(x + ey, p).x() + curl_noise_flow(x - ey, p).x()) /
                       (2 * p.h);
      vort_max = wbtest::worst_of(vort_max, std::abs(w));
    }
    CAPTURE(with_obstacles, u_max, vort_max);
    {
      INFO(
          "the flow must not be zero: u = (dpsi/dy, -dpsi/dx) of a noise potential has "
          "speeds of about 1.5 m/s");
      REQUIRE(wbtest::finite(u_max) > 0.1);
    }
    const double tol = kDivRoundoffFactor * kEps * u_max / p.h;
    INFO(
        "div u measured by central differences with the flow's own step h must cancel to "
        "rounding: u = (dpsi/dy, -dpsi/dx) exactly (a swapped sign in one component, or the "
        "gradient (dpsi/dx, dpsi/dy) instead of the curl, leaves a divergence as large as the "
        "vorticity)\n  largest |div u| "
        << div_max << " 1/s, allowed " << tol << " (largest |vorticity| " << vort_max << ")");
    REQUIRE(wbtest::finite(div_max) <= wbtest::finite(tol));
  }
}

TEST_CASE("F9 curl noise: the curl of the Rankine stream function is the F8 vortex flow",
          "[forces][F9][1pts]") {
  CurlNoiseParams p;
  p.psi = rankine_psi;
  p.h = 1e-5;
  // The F8 vortex's values (tests/forces/test_F8_vortex.cpp): inside the core
  // d = (0.6, 0.8): u = omega perp(d) = (-1.6, 1.2); outside d = (3, 4):
  // u = omega R^2 perp(d) / r^2 = (-1.28, 0.96); d = (-2.4, 1.8): (-1.6, -32/15).
  const char* what =
      "u = (dpsi/dy, -dpsi/dx) of psi = -omega r^2 / 2 is the solid rotation omega perp(d) "
      "(counter-clockwise for omega > 0); check the signs and the order of the components, "
      "and divide by 2h";
  wbtest::require_near(curl_noise_flow(Vec2(1.6, -0.2), p), Vec2(-1.6, 1.2), kFlowTol, what);
  wbtest::require_near(curl_noise_flow(Vec2(4, 3), p), Vec2(-1.28, 0.96), kFlowTol,
                       "outside the core the curl of psi = -omega R^2 ln r is "
                       "omega R^2 perp(d) / r^2");
  wbtest::require_near(curl_noise_flow(Vec2(-1.4, 0.8), p), Vec2(-1.6, -32.0 / 15), kFlowTol,
                       "outside the core the curl of psi = -omega R^2 ln r is "
                       "omega R^2 perp(d) / r^2");
}

TEST_CASE("F9 curl noise: psi is ramped to zero at the nearest obstacle's edge",
          "[forces][F9][1pts]") {
  CurlNoiseParams p;
  p.psi = [](const Vec2&) { return 2.0; };  // a constant psi shows the ramp alone
  p.h = 1e-5;
  {
    const double got = curl_noise_potential(Vec2(0.3, -7), p);
    INFO("with no obstacles psi_c = psi, here 2\n  got " << got);
    REQUIRE(got == 2.0);
  }
  p.obstacles = {{Vec2(0, 0), 1.0}, {Vec2(5, 0), 0.5}};
  p.ramp = 2.0;
  struct Case {
    Vec2 x;
    double expected;
    const char* why;
  };
  const Case cases[] = {
      {Vec2(0.6, 0.8), 0.0, "on the edge of disc 0 (d = 0): psi_c = ramp(0) psi = 0"},
      {Vec2(2, 0), 2 * kRampHalf,
       "d = |x - center| - radius = 1 to disc 0, d / d0 = 1/2: psi_c = ramp(1/2) psi"},
      {Vec2(4, 0), 2 * kRampQuarter,
       "d = 0.5 to disc 1 (3 to disc 0): the NEAREST edge counts, ramp(1/4) psi"},
      {Vec2(-4, 0), 2.0, "d / d0 = 1.5 >= 1: far from every obstacle ramp = 1, psi_c = psi"},
      {Vec2(0, 0.5), -2 * kRampQuarter, "inside disc 0, d = -0.5: ramp(-1/4) = -ramp(1/4)"},
  };
  for (const Case& c : cases) {
    wbtest::require_near(curl_noise_potential(c.x, p), c.expected, kTol,
                         std::string("psi_c = ramp(d / d0) psi with ramp(s) = 15/8 s - 10/8 s^3 "
                                     "+ 3/8 s^5 for |s| < 1: ") +
                             c.why + " (at " + wbtest::str(c.x) + ")");
  }
}

TEST_CASE("F9 curl noise: psi inside an obstacle larger than the ramp distance",
          "[forces][F9][1pts]") {
  // A disc of radius 3 with d0 = 1: deeper than d0 inside it, s = d / d0 <= -1 and the
  // ramp is held at -1 (the polynomial turns back beyond |s| = 1: at s = -2.5 it is -21.8).
  CurlNoiseParams p;
  p.psi = [](const Vec2& x) { return 0.5 * x.y() - 2.0 * x.x(); };  // uniform u = (0.5, 2)
  p.h = 0.25;  // a power of two: differences of this linear psi are exact
  p.obstacles = {{Vec2(0, 0), 3.0}};
  p.ramp = 1.0;
  struct Case {
    Vec2 x;
    double ramp;
    const char* why;
  };
  const Case cases[] = {
      {Vec2(0, 0.5), -1.0, "d = -2.5, s = -2.5 <= -1: ramp = -1"},
      {Vec2(-1.5, 0), -1.0, "d = -1.5, s = -1.5 <= -1: ramp = -1"},
      {Vec2(0, -2.5), -kRampHalf, "d = -0.5, s = -1/2: ramp(-1/2) = -ramp(1/2)"},
  };
  for (const Case& c : cases) {
    wbtest::require_near(curl_noise_potential(c.x, p), c.ramp * p.psi(c.x), kTol,
                         std::string("psi_c = ramp(d / d0) psi, ramp(s) = -1 for s <= -1: ") +
                             c.why + " (at " + wbtest::str(c.x) + ")");
  }
  wbtest::require_near(curl_noise_flow(Vec2(0, 0.5), p), Vec2(-0.5, -2.0), kTol,
                       "deep inside (ramp = -1 all around) the flow is the curl of -psi: "
                       "-(0.5, 2)");
}

TEST_CASE("F9 curl noise: the nearest edge counts and not the nearest centre",
          "[forces][F9][1pts]") {
  // At x = (1, 0): the small disc's centre is nearer (1 against 2.5), the large disc's
  // EDGE is nearer (0.5 against 0.8). d is the smallest distance to an edge: 0.5, and
  // with d0 = 2, s = 1/4. In either order of the list.
  CurlNoiseParams p;
  p.psi = [](const Vec2&) { return 2.0; };
  p.h = 1e-5;
  p.ramp = 2.0;
  const Disc small{Vec2(0, 0), 0.2}, large{Vec2(3.5, 0), 2.0};
  for (int order = 0; order < 2; ++order) {
    p.obstacles = order == 0 ? std::vector<Disc>{small, large} : std::vector<Disc>{large, small};
    wbtest::require_near(curl_noise_potential(Vec2(1, 0), p), 2 * kRampQuarter, kTol,
                         std::string("d = min over the discs of (|x - center| - radius) = 0.5 "
                                     "(the large disc's edge; the small disc's centre is "
                                     "nearer but its edge is 0.8 away): psi_c = ramp(1/4) psi, "
                                     "obstacles listed ") +
                             (order == 0 ? "small first" : "large first"));
  }
}

TEST_CASE("F9 curl noise: the central differences use the step h", "[forces][F9][1pts]") {
  // psi = y^3 - 2 x^3: the central difference with step h is exact up to h^2,
  //   (psi(y + h) - psi(y - h)) / (2h) = 3 y^2 + h^2,  along x: -6 x^2 - 2 h^2,
  // so u = (3 y^2 + h^2, 6 x^2 + 2 h^2) with the field's own h. All values below are
  // exact binary fractions: the computation is exact.
  CurlNoiseParams p;
  p.psi = [](const Vec2& x) { return x.y() * x.y() * x.y() - 2.0 * x.x() * x.x() * x.x(); };
  const Vec2 x(0.5, -1.5);
  for (double h : {0.5, 0.125}) {
    p.h = h;
    wbtest::require_near(curl_noise_flow(x, p), Vec2(3 * 2.25 + h * h, 6 * 0.25 + 2 * h * h),
                         kTol,
                         "central differences with the field's step p.h = " + std::to_string(h) +
                             " (not a step of your own): u = (3 y^2 + h^2, 6 x^2 + 2 h^2) for "
                             "psi = y^3 - 2 x^3 at (0.5, -1.5)");
  }
}

TEST_CASE("F9 curl noise: the flow is tangent to an obstacle and slips along it",
          "[forces][F9][1pts]") {
  CurlNoiseParams p = noise_field(3);
  p.h = 1e-5;
  p.ramp = 0.8;
  const Disc disc{Vec2(0.5, -0.3), 1.0};
  p.obstacles = {disc};
  // On the edge psi_c = 0 and grad psi_c = ramp'(0) psi / d0 n = 15/8 psi / d0 n
  // (n the outward normal), so u = 15/8 psi(x) / d0 (n_y, -n_x): along the edge.
  for (int k = 0; k < 12; ++k) {
    const double a = 2 * 3.14159265358979323846 * (k + 0.25) / 12;
    const Vec2 n(std::cos(a), std::sin(a));
    const Vec2 x = disc.center + disc.radius * n;
    const Vec2 u = curl_noise_flow(x, p);
    CAPTURE(k, wbtest::str(x));
    {
      INFO(
          "the flow must not cross the edge of an obstacle: u . n = dpsi_c/dtangent = 0 "
          "there, since psi_c = 0 all along the edge\n  u . n = "
          << u.dot(n) << " m/s, u = " << wbtest::str(u));
      REQUIRE(wbtest::finite(std::abs(u.dot(n))) <= kFlowTol);
    }
    wbtest::require_near(
        u, (15.0 / 8) * p.psi(x) / p.ramp * Vec2(n.y(), -n.x()), kFlowTol,
        "on the edge the flow slips along it with u = 15/8 psi / d0 (n_y, -n_x): "
        "ramp psi itself (not the velocity) so the edge is a streamline");
  }
}

TEST_CASE("F9 curl noise: drag b (u - v) pulls every particle towards the flow",
          "[forces][F9][1pts]") {
  CurlNoiseParams p;
  p.psi = [](const Vec2& x) { return 0.5 * x.y() - 2.0 * x.x(); };  // uniform u = (0.5, 2)
  p.b = 2.5;
  p.h = 0.25;  // a power of two: differences of this linear psi are exact
  // Particle 0 at rest: f = 2.5 (0.5, 2) = (1.25, 5); 1 moves with the flow: 0;
  // 2 with v = (1, -1): 2.5 (-0.5, 3) = (-1.25, 7.5); 3 at rest: (1.25, 5).
  Mat2X x(2, 4), v(2, 4), f(2, 4);
  x << 1.0, -2.0, 0.5, 3.0,  //
      0.0, 1.0, 4.0, -1.5;
  v << 0.0, 0.5, 1.0, 0.0,  //
      0.0, 2.0, -1.0, 0.0;
  f << 2.0, 1.0, 4.0, 3.0,  // forces already there: add to them
      0.0, -1.0, 0.25, 0.5;
  add_curl_noise(x, v, p, f);
  Mat2X expected(2, 4);
  expected << 2.0 + 1.25, 1.0, 4.0 - 1.25, 3.0 + 1.25,  //
      5.0, -1.0, 0.25 + 7.5, 0.5 + 5.0;
  wbtest::require_near(f, expected, kTol,
                       "drag towards the flow: f_i += b (u(x_i) - v_i) for EVERY particle i "
                       "(first and last included), times b, added to f",
                       kTol);
}

TEST_CASE("F9 curl noise: the same seed gives the same forces and another seed another flow",
          "[forces][F9][1pts]") {
  const Mat2X x = wbtest::random_points(50, 5, -4.0, 4.0);
  const Mat2X v = wbtest::random_points(50, 6, -1.0, 1.0);
  auto forces = [&](std::uint64_t seed) {
    CurlNoiseParams p = noise_field(seed);  // built afresh for every call
    p.obstacles = {{Vec2(1, 1), 0.8}};
    Mat2X f = Mat2X::Zero(2, x.cols());
    add_curl_noise(x, v, p, f);
    return f;
  };
  const Mat2X a = forces(11), b = forces(11), c = forces(12);
  wbtest::require_finite(a, "curl-noise drag on 50 particles");
  {
    INFO(
        "two fields built from the same seed must give bit-identical forces (no hidden "
        "state, no randomness of your own): largest difference "
        << (a - b).cwiseAbs().maxCoeff() << " N");
    REQUIRE(wbtest::max_abs_diff(a, b) == 0.0);  // NaN fails
  }
  {
    INFO("another seed is another noise: the forces must change (largest difference "
         << (a - c).cwiseAbs().maxCoeff() << " N); is psi = p.psi used?");
    REQUIRE(std::isfinite(wbtest::max_abs_diff(a, c)));  // NaN or inf: no flow
    REQUIRE(wbtest::max_abs_diff(a, c) > 1e-3);
  }
}

TEST_CASE("F9 held-out: random fields and obstacles give the ramped psi and its curl",
          "[forces][F9][held-out][2pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("F9")) {
    INFO(g.replay());
    // Two fields in turn (a copy of the first kept by the lab's code computes the first), with
    // steps far apart (a step of one's own matches at most one of them): field 0 a small step,
    // its obstacles a small disc whose centre is nearer and a large disc whose edge is nearer;
    // field 1 a large step, an obstacle wider than twice the ramp with a point deep inside.
    for (int field = 0; field < 2; ++field) {
      CurlNoiseParams p;
      // A smooth psi of the test's own: a constant, a plane wave, a quadratic and a cubic (the
      // cubic's central differences carry h^2, so the step shows), random each time.
      const double c0 = g.sign() * g.uniform(1.0, 2.0), a = g.uniform(0.1, 0.4);
      const Vec2 k = g.vec2(-1.5, 1.5), q = g.vec2(-0.3, 0.3), c3 = g.vec2(-0.2, 0.2);
      const double phase = g.uniform(0.0, 6.0);
      p.psi = [=](const Vec2& y) {
        return c0 + a * std::sin(k.dot(y) + phase) + q.x() * y.x() * y.y() +
               q.y() * y.y() * y.y() + c3.x() * y.x() * y.x() * y.x() +
               c3.y() * y.y() * y.y() * y.y();
      };
      p.b = g.uniform(0.2, 3.0);
      p.h = field == 0 ? g.log_uniform(1e-5, 1e-3) : g.uniform(0.05, 0.4);
      p.ramp = field == 0 ? g.uniform(1.2, 2.0) : g.uniform(0.3, 0.6);
      const Eigen::Index n = g.integer(6, 9);
      Mat2X x = g.points(n, -4.0, 4.0);
      if (field == 0) {
        // At x_0 (near the origin): a small disc's centre at dist, its edge at dist - rs; a
        // large disc's centre further, its edge nearer, at dist - rs - e (inside the ramp).
        x.col(0) = g.vec2(-1.0, 1.0);
        const double dist = g.uniform(0.6, 1.0), rs = g.uniform(0.05, 0.2),
                     e = g.uniform(0.1, 0.3);
        const double far = dist + g.uniform(0.5, 1.5);
        p.obstacles.push_back({Vec2(x.col(0)) + dist * g.unit2(), rs});
        p.obstacles.push_back({Vec2(x.col(0)) + far * g.unit2(), far - (dist - rs - e)});
        if (g.coin()) std::swap(p.obstacles[0], p.obstacles[1]);  // in either order
      } else {
        p.obstacles.push_back({g.vec2(-3, 3), p.ramp * g.uniform(2.2, 3.0)});
        p.obstacles.push_back({g.vec2(-3, 3), g.uniform(0.3, 1.2)});
        // Deep inside the wide disc (d < -ramp: psi_c = -psi), and in its ramp band inside.
        const Disc& o = p.obstacles[0];
        x.col(0) = o.center + (o.radius - g.uniform(1.1, 1.8) * p.ramp) * g.unit2();
        x.col(1) = o.center + (o.radius - g.uniform(0.1, 0.9) * p.ramp) * g.unit2();
      }
      // About the last obstacle: one inside it, one in its ramp band, one beyond the band.
      const Disc& o = p.obstacles.back();
      x.col(2) = o.center + g.uniform(0.1, 0.9) * o.radius * g.unit2();
      x.col(3) = o.center + (o.radius + g.uniform(0.1, 0.9) * p.ramp) * g.unit2();
      x.col(4) = o.center + (o.radius + g.uniform(1.2, 2.0) * p.ramp) * g.unit2();
      auto psi_c = [&](const Vec2& y) {
        double d = std::numeric_limits<double>::infinity();
        for (const Disc& ob : p.obstacles)
          d = wbtest::least_of(d, (y - ob.center).norm() - ob.radius);
        const double s = std::clamp(d / p.ramp, -1.0, 1.0);
        return (15.0 / 8 * s - 10.0 / 8 * s * s * s + 3.0 / 8 * s * s * s * s * s) * p.psi(y);
      };
      const Mat2X v = g.points(n, -2.0, 2.0), f0 = g.points(n, -3.0, 3.0);
      Mat2X expected = f0;
      for (Eigen::Index i = 0; i < n; ++i) {
        const Vec2 y = x.col(i), ex(p.h, 0), ey(0, p.h);
        INFO("field " << field << ", at x = " << wbtest::str(y) << ", obstacles "
                      << wbtest::str(p.obstacles[0].center) << " radius " << p.obstacles[0].radius
                      << " and " << wbtest::str(p.obstacles[1].center) << " radius "
                      << p.obstacles[1].radius << ", ramp " << p.ramp << ", h = " << p.h);
        const double pc = psi_c(y);
        wbtest::require_near(curl_noise_potential(y, p), pc, 1e-12 * (1.0 + std::abs(pc)),
                             "psi_c = ramp(d / d0) psi, d the distance to the nearest edge "
                             "(signed: negative inside a disc)");
        const Vec2 u((psi_c(y + ey) - psi_c(y - ey)) / (2 * p.h),
                     -(psi_c(y + ex) - psi_c(y - ex)) / (2 * p.h));
        // Differences of values rounded to ~1e-16 |psi| over 2h: 1e-11 of |psi| / h is ample
        // (and far below a first-order difference's error, h |psi''| / 2, or that of another
        // step h', |h^2 - h'^2| |psi'''| / 6).
        const double tol = 1e-11 * (1.0 + std::abs(pc)) / p.h;
        wbtest::require_near(curl_noise_flow(y, p), u, tol,
                             "u = (dpsi_c/dy, -dpsi_c/dx) by central differences with the "
                             "field's step h");
        expected.col(i) += p.b * (u - v.col(i));
      }
      Mat2X f = f0;
      add_curl_noise(x, v, p, f);
      INFO("x = " << x << "\n  v = " << v << "\n  b = " << p.b);
      wbtest::require_near(f, expected, 1e-7 / p.h, "f_i += b (u(x_i) - v_i) for every particle");
    }
  }
}

}  // namespace test_F9_curl_noise
