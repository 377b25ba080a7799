// Graded tests for TODO(E1), the explicit Euler step (labs/euler/explicit_euler.cpp).
// Expected values come from the step's definition x' = x + h v, v' = v + h a(x, v)
// and what it implies in closed form; never from a run of the solution.
#include <cmath>

#include "euler_kernels.h"
#include "euler_test_helpers.h"
#include "explicit_euler.h"

// The checks E1 and E2 share are euler_test_helpers.h's; what stays alike in the two files is
// each task's list of test cases, its names, tags and points (docs/contributor.md, "Repeated
// code").
// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace explicit_euler_test {

using namespace eulertest;
using wbtest::require_near;

namespace {

// One step is a handful of additions: a few ulps of the largest term.
constexpr double kStepTol = 1e-14;
// A ratio of two energies each rounded to ~1e-16 relative, a few times over.
constexpr double kRatioTol = 1e-12;
// 10^6 steps each adding ~1e-16 relative rounding: the worst case is ~1e-10.
constexpr double kLongRunTol = 1e-8;

// The scenarios of the public tests below, each a function of its parameters: the public test
// runs it with the published ones (wbtest::Params()), the held-out test with drawn ones, in the
// same format (tests/common/params.h).

void one_step(const wbtest::Params& p) {
  const OneStep c(p);  // accelerations that depend on x and v, different for every particle
  const Mat2X &x0 = c.x0, &v0 = c.v0, &a0 = c.a0;
  const double h = c.h;

  Run r(c.accel, x0, v0);
  r.step(explicit_euler_step, h);
  require_near(r.x, Mat2X(x0 + h * v0), kStepTol,
               "explicit Euler position x1 = x0 + h v0 (the velocity at the START of the step)",
               kStepTol);
  require_near(r.v, Mat2X(v0 + h * a0), kStepTol, "explicit Euler velocity v1 = v0 + h a(x0, v0)",
               kStepTol);
}

// For a = -(k/m) x:  E' = 1/2 m (v + h a)^2 + 1/2 k (x + h v)^2
//                       = (1 + h^2 k/m) E   (the cross terms cancel),
// so the orbit spirals out at EVERY step size, however small.
// Held-out: m, k (w within 25 % of the published 2, the speeds' magnitudes with it), the start
// and each case's h drawn (h w within 20 % of the published h w), the
// cases' steps cut to the share of calls the public test has (300 of its 5040, as
// tools/adversary --inputs samples them).
void oscillator_energy_growth(const wbtest::Params& p) {
  const double m = p.num(2.5, 2.0, 3.0), k = p.num(10.0, 8.0, 12.0), w = std::sqrt(k / m);
  struct Case {
    double hw;
    int steps, held_out_steps;
  };
  // hw = 1000/60: the stiff spring of scenes/euler/stiff-spring.json at h = 1/60.
  for (Case c :
       {Case{0.001, 2000, 120}, Case{0.01, 2000, 120}, Case{0.1, 500, 30}, Case{0.5, 200, 12},
        Case{1.0, 200, 12}, Case{2.5, 100, 6}, Case{1000.0 / 60.0, 40, 3}}) {
    // The published h is c.hw / 2 (w = 2 exactly), and a draw takes its digits: c.hw / w of
    // the drawn w has 17, and its steps' calls, their only short decimal gone, told the
    // held-out calls apart (tools/adversary --inputs).
    const double h = p.num(c.hw / 2.0, 0.8 * c.hw / w, 1.2 * c.hw / w);
    const double hw = h * w;  // c.hw in the public test
    const double factor = 1.0 + hw * hw;
    INFO("h w = " << hw << " (h = " << h << ")");
    // The start: a state of the published start's ellipse at a drawn phase (0 in the public
    // test), so that the held-out test's short runs see every phase, as the public test's long
    // ones do.
    const Vec2 xp(p.num(0.7, 0.5, 0.9), p.num(-0.3, -0.4, -0.2)),
        vp(p.num(0.2, 0.1, 0.3), p.num(0.5, 0.4, 0.6));
    const double phase = p.num(0.0, 0.0, 6.28);
    const Vec2 x0 = xp * std::cos(phase) + vp / w * std::sin(phase),
               v0 = vp * std::cos(phase) - w * xp * std::sin(phase);
    Run r(oscillator(w),
          cols({{wbtest::Params::short_decimal(x0.x()), wbtest::Params::short_decimal(x0.y())}}),
          cols({{wbtest::Params::short_decimal(v0.x()), wbtest::Params::short_decimal(v0.y())}}));
    double E = oscillator_energy(r.x, r.v, m, k);
    const long steps = p.steps(c.steps, c.held_out_steps);
    for (long n = 1; n <= steps; ++n) {
      r.step(explicit_euler_step, h);
      const double E1 = oscillator_energy(r.x, r.v, m, k);
      INFO("step " << n);
      require_near(E1 / E, factor, 0.0,
                   "explicit Euler multiplies E = 1/2 m v^2 + 1/2 k x^2 by 1 + (h w)^2 each step",
                   kRatioTol);
      E = E1;
    }
  }
}

wb::Mat2 step_matrix(double h, double w) {
  wb::Mat2 M;  // (x, v) -> (x + h v, v - h w^2 x)
  M << 1.0, h, -h * w * w, 1.0;
  return M;
}

// A central force a = -GM x/r^3 has x cross a = 0, so for x' = x + h v,
// v' = v + h a:  L' = (x + h v) cross (v + h a) = L + h^2 v cross a = L (1 + h^2 GM / r^3).
// The orbit (e = 0.9, started at periapsis r = 0.1) gains angular momentum
// fastest where it passes closest.
// Held-out: GM, a, e and h drawn, 300 steps (the share of calls the public test's 2000 have, as
// tools/adversary --inputs samples them) of a larger h, so that the run reaches about as far.
void eccentric_orbit(const wbtest::Params& p) {
  const double GM = p.num(1.0, 0.9, 1.1), e = p.num(0.9, 0.85, 0.9), a = p.num(1.0, 0.9, 1.1),
               h = p.num(1e-3, 3e-3, 5e-3);
  const double rp = a * (1.0 - e), vp = std::sqrt(GM * (1.0 + e) / rp);
  Run r(attractor(GM), cols({{rp, 0.0}}), cols({{0.0, vp}}));
  double L = wb::cross(r.x.col(0), r.v.col(0));
  const long steps = p.steps(2000, 300);
  for (long n = 1; n <= steps; ++n) {
    const double radius = r.x.col(0).norm();
    r.step(explicit_euler_step, h);
    const double L1 = wb::cross(r.x.col(0), r.v.col(0));
    INFO("step " << n << ", r = " << radius);
    require_near(L1 / L, 1.0 + h * h * GM / (radius * radius * radius), 0.0,
                 "explicit Euler: L_{n+1} = L_n (1 + h^2 GM / r_n^3) for a central force",
                 kRatioTol);
    L = L1;
  }
}

// At h w = 10^-3 each step gains only 10^-6 of the energy, yet after 10^6
// steps the energy has grown by (1 + 10^-6)^(10^6), almost e.
// Held-out: w, h (h w within 20 % of 10^-3) and the start drawn, 2 10^4 steps (one call either
// way: its length is no input's property, and the held-out test's time stays small).
void long_run(const wbtest::Params& p) {
  const double w = p.num(2.0, 1.0, 3.0), h = p.num(5e-4, 8e-4 / w, 1.2e-3 / w), hw = h * w,
               m = 1.0, k = w * w;
  const long N = p.steps(1000000, 20000), every = 1000;
  const Mat2X x0 = cols({{p.num(1.0, 0.5, 1.5), p.num(0.0, -0.5, 0.5)}}),
              v0 = cols({{p.num(0.0, -0.5, 0.5), p.num(0.5, 0.2, 0.8)}});
  Run r(oscillator(w), x0, v0);
  const double E0 = oscillator_energy(r.x, r.v, m, k);
  Mat2X xs, vs;  // one call for the whole loop, its states every 1000 steps (euler_kernels.h)
  euler_oscillator_run(0, w, h, N, every, r.x, r.v, xs, vs);
  check_long_run(false, w, h, x0, v0, N, every, r.x, r.v, xs, vs,
                 p.held_out() ? "explicit Euler, the held-out run" : "explicit Euler, 10^6 steps",
                 [&](long c, const Mat2X& x, const Mat2X& v) {
                   require_near(oscillator_energy(x, v, m, k) / E0,
                                std::pow(1.0 + hw * hw, double(c * every)), 0.0,
                                "explicit Euler energy E_n = (1 + (h w)^2)^n E_0", kLongRunTol);
                 });
  require_near(oscillator_energy(r.x, r.v, m, k) / E0, std::pow(1.0 + hw * hw, double(N)), 0.0,
               p.held_out() ? "explicit Euler energy at the end of the held-out run"
                            : "explicit Euler energy after 10^6 steps at h w = 10^-3",
               kLongRunTol);
}

}  // namespace

TEST_CASE("E1 one step: positions move with the old velocities", "[euler][E1][6pts]") {
  one_step(wbtest::Params());
}

TEST_CASE("E1 harmonic oscillator: energy grows by exactly 1 + (h w)^2 per step",
          "[euler][E1][8pts]") {
  oscillator_energy_growth(wbtest::Params());
}

TEST_CASE("E1 free fall: x_n = x0 + v0 t + g t^2/2 - g h t/2", "[euler][E1][5pts]") {
  // With a = g: v_n = v0 + g t_n exactly, and x_n = x0 + h (v_0 + ... + v_{n-1})
  //   = x0 + v0 t_n + g h^2 n(n-1)/2 = x0 + v0 t_n + 1/2 g t_n^2 - 1/2 g h t_n.
  check_free_fall(wbtest::Params(), explicit_euler_step, false, "explicit Euler");
}

TEST_CASE("E1 viscous damping: velocities decay by 1 - h b/m per step", "[euler][E1][6pts]") {
  // a_i = -(b / m_i) v_i: v_n = r_i^n v0 with r_i = 1 - h b / m_i (distinct masses),
  // and x_n = x0 + h v0 (1 + r + ... + r^(n-1)) = x0 + h v0 (1 - r^n) / (1 - r).
  check_damping(wbtest::Params(), explicit_euler_step, false, "explicit Euler");
}

TEST_CASE("E1 one force evaluation per step at the start of the step", "[euler][E1][5pts]") {
  // Explicit Euler needs a(x_n, v_n) only: one call per step, at the old state.
  check_one_evaluation_at_start(wbtest::Params(), explicit_euler_step, "explicit Euler");
}

TEST_CASE("E1 several particles step independently", "[euler][E1][4pts]") {
  check_independent_particles(wbtest::Params(), explicit_euler_step, step_matrix,
                              "[1 h, -h w^2 1]");
}

TEST_CASE("E1 eccentric orbit: angular momentum grows by 1 + h^2 GM/r^3 per step",
          "[euler][E1][5pts]") {
  eccentric_orbit(wbtest::Params());
}

TEST_CASE("E1 long run: 10^6 steps follow E_n = (1 + (h w)^2)^n E_0", "[euler][E1][3pts]") {
  long_run(wbtest::Params());
}

// Every public scenario above again, its parameters drawn from the held-out seed in the public
// tests' format (short decimals, the same particle counts within one, about the same
// magnitudes, each scenario's calls in the share they have among the public tests' calls), so
// that no call tells the public tests from this one (tools/adversary --inputs).
TEST_CASE("E1 held-out: the public scenarios with drawn parameters",
          "[euler][E1][held-out][8pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("E1")) {
    INFO(g.replay());
    const wbtest::Params p(g);
    one_step(p);
    oscillator_energy_growth(p);
    check_free_fall(p, explicit_euler_step, false, "explicit Euler");
    check_damping(p, explicit_euler_step, false, "explicit Euler");
    check_one_evaluation_at_start(p, explicit_euler_step, "explicit Euler");
    check_independent_particles(p, explicit_euler_step, step_matrix, "[1 h, -h w^2 1]");
    eccentric_orbit(p);
    long_run(p);
  }
}

}  // namespace explicit_euler_test
