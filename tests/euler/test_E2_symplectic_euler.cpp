// Graded tests for TODO(E2), the semi-implicit Euler step (labs/euler/symplectic_euler.cpp).
// Expected values come from the step's definition v' = v + h a(x, v), x' = x + h v'
// and what it implies in closed form; never from a run of the solution.
#include <algorithm>
#include <cmath>

#include "euler_kernels.h"
#include "euler_test_helpers.h"
#include "symplectic_euler.h"

// The checks E1 and E2 share are euler_test_helpers.h's; what stays alike in the two files is
// each task's list of test cases, its names, tags and points (docs/contributor.md, "Repeated
// code").
// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace symplectic_euler_test {

using namespace eulertest;
using wbtest::require_near;

namespace {

// One step is a handful of additions: a few ulps of the largest term.
constexpr double kStepTol = 1e-14;
// A conserved quantity over ~10^4 steps: rounding adds ~1e-16 relative per step.
constexpr double kConservedTol = 1e-11;
// Over 10^6 steps the rounding of a conserved quantity stays below ~1e-10.
constexpr double kLongRunTol = 1e-9;

// For hw < 2 the discrete oscillator's energy E = Q / (1 - (hw/2) sin 2phi)
// sweeps [Q/(1 + hw/2), Q/(1 - hw/2)] as the phase phi turns (see
// handouts/euler.md): the relative wobble max E / min E - 1.
double predicted_wobble(double hw) { return (1.0 + 0.5 * hw) / (1.0 - 0.5 * hw) - 1.0; }

}  // namespace

TEST_CASE("E2 one step: velocities first then positions with the new velocities",
          "[euler][E2][6pts]") {
  const OneStep c;  // accelerations that depend on x and v, different for every particle
  const Mat2X &x0 = c.x0, &v0 = c.v0, &a0 = c.a0;
  const double h = c.h;
  const Mat2X v1 = v0 + h * a0;

  Run r(c.accel, x0, v0);
  r.step(symplectic_euler_step, h);
  require_near(r.v, v1, kStepTol, "semi-implicit Euler velocity v1 = v0 + h a(x0, v0)", kStepTol);
  require_near(r.x, Mat2X(x0 + h * v1), kStepTol,
               "semi-implicit Euler position x1 = x0 + h v1 (the NEW velocity)", kStepTol);
}

TEST_CASE("E2 harmonic oscillator: modified energy conserved and energy bounded for h w below 2",
          "[euler][E2][6pts]") {
  // For v' = v - h w^2 x, x' = x + h v' the quantity
  //   Q = 1/2 m v^2 + 1/2 k x^2 - 1/2 h k x v        (k = m w^2)
  // is conserved exactly (expand Q(x', v') - Q(x, v): every term cancels).
  // The true energy E = Q + 1/2 h k x v wobbles around it without drifting.
  const double m = 0.8, k = 20.0, w = std::sqrt(k / m);
  for (double hw : {0.01, 0.1, 0.5, 1.0, 1.5, 1.99}) {
    const double h = hw / w;
    INFO("h w = " << hw << " (h = " << h << ")");
    Run r(oscillator(w), cols({{0.6, -0.2}}), cols({{1.5, 0.4}}));
    auto Q = [&] {
      return oscillator_energy(r.x, r.v, m, k) - 0.5 * h * k * r.x.col(0).dot(r.v.col(0));
    };
    const double Q0 = Q();
    double Emin = oscillator_energy(r.x, r.v, m, k), Emax = Emin;
    for (int n = 1; n <= 5000; ++n) {
      r.step(symplectic_euler_step, h);
      INFO("step " << n);
      require_near(Q(), Q0, 0.0,
                   "semi-implicit Euler conserves Q = 1/2 m v^2 + 1/2 k x^2 - 1/2 h k x.v",
                   kConservedTol);
      const double E = oscillator_energy(r.x, r.v, m, k);
      require_near(E, 0.5 * (Q0 / (1.0 + 0.5 * hw) + Q0 / (1.0 - 0.5 * hw)),
                   0.5 * (Q0 / (1.0 - 0.5 * hw) - Q0 / (1.0 + 0.5 * hw)) * (1.0 + 1e-9),
                   "energy bounded: Q/(1 + h w/2) <= E <= Q/(1 - h w/2)");
      Emin = wbtest::least_of(Emin, E);
      Emax = wbtest::worst_of(Emax, E);
    }
    // The orbit really turns: over 5000 steps the phase visits angles all
    // around, so the energy sweeps a good part of its predicted range (near
    // h w = 2 the extremes are sharp peaks that discrete samples only graze,
    // hence a quarter of the range).
    INFO("energy range max/min - 1 = " << Emax / Emin - 1.0 << ", predicted "
                                       << predicted_wobble(hw));
    REQUIRE(wbtest::finite(Emax / Emin - 1.0) >= 0.25 * predicted_wobble(hw));
  }
}

TEST_CASE(
    "E2 harmonic oscillator: each step turns the phase by theta with cos theta = 1 - (h w)^2/2",
    "[euler][E2][4pts]") {
  // The step matrix M = [1 - (hw)^2, h; -h w^2, 1] has det 1 and trace
  // 2 - (hw)^2 = 2 cos theta. By Cayley-Hamilton x_{n+1} = 2 cos theta x_n - x_{n-1},
  // so x_n = x0 cos(n theta) + (x1 - x0 cos theta) / sin theta sin(n theta)
  // with x1 = (1 - (hw)^2) x0 + h v0.
  const double w = 3.0;
  for (double hw : {0.05, 0.7, 1.9}) {
    const double h = hw / w;
    const double theta = std::acos(1.0 - 0.5 * hw * hw);
    const Vec2 x0(1.0, -0.5), v0(0.3, 2.0);
    const Vec2 x1 = (1.0 - hw * hw) * x0 + h * v0;
    Run r(oscillator(w), cols({x0}), cols({v0}));
    const double amplitude = 1.0 + v0.norm() / w;
    for (int n = 1; n <= 2000; ++n) {
      r.step(symplectic_euler_step, h);
      const Vec2 xe = x0 * std::cos(n * theta) +
                      (x1 - x0 * std::cos(theta)) / std::sin(theta) * std::sin(n * theta);
      INFO("h w = " << hw << ", step " << n);
      // Rounding of n theta grows like n * 1e-16: 1e-10 of the amplitude is ample.
      require_near(Vec2(r.x.col(0)), xe, 1e-10 * amplitude,
                   "semi-implicit Euler oscillator x_n = x0 cos(n theta) + B sin(n theta)");
    }
  }
}

TEST_CASE("E2 harmonic oscillator above h w = 2 grows by the step matrix's largest eigenvalue",
          "[euler][E2][4pts]") {
  // For hw > 2 the trace 2 - (hw)^2 < -2: both eigenvalues are real, negative,
  // with product 1. The larger one in size,
  //   lambda = (2 - (hw)^2 - sqrt((2 - (hw)^2)^2 - 4)) / 2,
  // takes over: x_{n+1} / x_n -> lambda (the sign flips every step).
  const double w = 1000.0;  // k/m = 10^6 as in scenes/euler/stiff-spring.json
  for (double hw : {2.5, 3.0, 1000.0 / 60.0}) {
    const double h = hw / w;
    const double tr = 2.0 - hw * hw;
    const double lambda = 0.5 * (tr - std::sqrt(tr * tr - 4.0));
    Run r(oscillator(w), cols({{0.01, 0.0}}), cols({{0.0, 0.0}}));
    double prev = r.x(0, 0);
    for (int n = 1; n <= 30; ++n) {
      r.step(symplectic_euler_step, h);
      if (n >= 25) {  // (1/lambda^2)^24 is below 1e-9 for every case
        INFO("h w = " << hw << ", step " << n);
        require_near(r.x(0, 0) / prev, lambda, 0.0,
                     "growth per step x_{n+1}/x_n -> lambda, the eigenvalue of the step matrix",
                     1e-8);
      }
      prev = r.x(0, 0);
    }
  }
}

TEST_CASE("E2 free fall: x_n = x0 + v0 t + g t^2/2 + g h t/2", "[euler][E2][5pts]") {
  // With a = g: v_n = v0 + g t_n exactly, and x_n = x0 + h (v_1 + ... + v_n)
  //   = x0 + v0 t_n + g h^2 n(n+1)/2 = x0 + v0 t_n + 1/2 g t_n^2 + 1/2 g h t_n:
  // the same error as explicit Euler with the opposite sign.
  check_free_fall(symplectic_euler_step, true, "semi-implicit Euler");
}

TEST_CASE("E2 viscous damping: velocities decay by 1 - h b/m per step", "[euler][E2][5pts]") {
  // a_i = -(b / m_i) v_i: v_n = r_i^n v0 with r_i = 1 - h b / m_i (distinct masses),
  // and x_n = x0 + h (v_1 + ... + v_n) = x0 + h v0 r (1 - r^n) / (1 - r).
  check_damping(symplectic_euler_step, true, "semi-implicit Euler");
}

TEST_CASE("E2 one force evaluation per step at the start of the step", "[euler][E2][4pts]") {
  // Semi-implicit Euler needs a(x_n, v_n) only: one call per step, at the old state.
  check_one_evaluation_at_start(symplectic_euler_step, "semi-implicit Euler");
}

TEST_CASE("E2 several particles step independently", "[euler][E2][3pts]") {
  check_independent_particles(
      symplectic_euler_step,
      [](double h, double w) {
        wb::Mat2 M;  // (x, v) -> (x + h v', v' = v - h w^2 x)
        M << 1.0 - h * h * w * w, h, -h * w * w, 1.0;
        return M;
      },
      "[1 - (hw)^2 h, -h w^2 1]");
}

TEST_CASE("E2 eccentric orbit: angular momentum conserved and energy error does not drift",
          "[euler][E2][3pts]") {
  // For a central force x cross a = 0, so v' = v + h a keeps x cross v, and
  // x' = x + h v' keeps it again: L is conserved to rounding. The energy error
  // is bounded (a modified energy is conserved), so it does not grow orbit after orbit.
  const double GM = 1.0, e = 0.9, a = 1.0, h = 1e-3;
  const double rp = a * (1.0 - e), vp = std::sqrt(GM * (1.0 + e) / rp);
  const double period = 2.0 * M_PI * std::sqrt(a * a * a / GM);
  const int per_orbit = int(std::lround(period / h));
  Run r(attractor(GM), cols({{rp, 0.0}}), cols({{0.0, vp}}));
  auto energy = [&] { return 0.5 * r.v.squaredNorm() - GM / r.x.norm(); };
  const double L0 = wb::cross(r.x.col(0), r.v.col(0)), E0 = energy();
  double first = 0, last = 0, rmax = 0;
  const int orbits = 10;
  for (int n = 1; n <= orbits * per_orbit; ++n) {
    r.step(symplectic_euler_step, h);
    const double dE = std::abs(energy() - E0);
    if (n <= per_orbit) first = wbtest::worst_of(first, dE);
    if (n > (orbits - 1) * per_orbit) last = wbtest::worst_of(last, dE);
    rmax = wbtest::worst_of(rmax, r.x.norm());
  }
  require_near(wb::cross(r.x.col(0), r.v.col(0)), L0, 0.0,
               "semi-implicit Euler conserves angular momentum L = x cross v (central force)",
               kConservedTol);
  // The particle must actually travel the orbit: apoapsis a (1 + e) = 1.9.
  require_near(rmax, a * (1.0 + e), 0.05, "largest distance reached = apoapsis a (1 + e)");
  INFO("largest |E - E0| in orbit 1: " << first << ", in orbit " << orbits << ": " << last);
  // No drift: the last orbit's error is no larger than the first's (50% margin
  // for where the samples fall on the orbit).
  REQUIRE(wbtest::finite(last) <= 1.5 * wbtest::finite(first));
}

TEST_CASE("E2 long run: 10^6 steps conserve the modified energy", "[euler][E2][2pts]") {
  const double w = 2.0, hw = 0.01, h = hw / w, m = 1.0, k = w * w;
  // About 10^6 steps, the energy sampled every 97th (the phase still visits every angle).
  const long every = 97, N = every * 10310;
  const Mat2X x0 = cols({{1.0, 0.0}}), v0 = cols({{0.0, 0.5}});
  Run r(oscillator(w), x0, v0);
  auto Q = [&](const Mat2X& x, const Mat2X& v) {
    return oscillator_energy(x, v, m, k) - 0.5 * h * k * x.col(0).dot(v.col(0));
  };
  const double Q0 = Q(r.x, r.v);
  // The loop, as one call (euler_kernels.h), its states every 97 steps.
  Mat2X xs, vs;
  euler_oscillator_run(1, w, h, N, every, r.x, r.v, xs, vs);
  check_long_run(true, w, h, x0, v0, N, every, r.x, r.v, xs, vs,
                 "semi-implicit Euler, 10^6 steps", [&](long, const Mat2X& x, const Mat2X& v) {
                   require_near(Q(x, v), Q0, 0.0, "the modified energy Q is conserved",
                                kLongRunTol);
                 });
  require_near(Q(r.x, r.v), Q0, 0.0, "modified energy Q after 10^6 semi-implicit Euler steps",
               kLongRunTol);
  // The energy's range, computed here from the run's states.
  double Emin = oscillator_energy(x0, v0, m, k), Emax = Emin;
  for (Eigen::Index c = 0; c < xs.cols(); ++c) {
    const double E = oscillator_energy(xs.col(c), vs.col(c), m, k);
    Emin = wbtest::least_of(Emin, E);
    Emax = wbtest::worst_of(Emax, E);
  }
  INFO("energy range max/min - 1 = " << Emax / Emin - 1.0);
  REQUIRE(wbtest::finite(Emax / Emin - 1.0) >= 0.5 * predicted_wobble(hw));
}

TEST_CASE("E2 held-out: every step of random systems is v' = v + h a then x' = x + h v'",
          "[euler][E2][held-out][8pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("E2")) {
    INFO(g.replay());
    check_random_steps(g, symplectic_euler_step, true, "semi-implicit Euler");
  }
}

}  // namespace symplectic_euler_test
