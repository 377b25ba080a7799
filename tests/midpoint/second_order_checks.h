// The checks shared by the midpoint (M1) and trapezoid (M2) tests. Every
// expected value comes from mathematics, not from a solution's output:
//
//   - the circular Kepler orbit has the exact solution x(t) = (cos t, sin t);
//   - on a linear force a = A-part, one step of either method is the matrix
//     I + hA + (hA)^2/2 (derived in handouts/midpoint.md), so the energy of an
//     undamped oscillator is multiplied by exactly 1 + (h w)^4/4;
//   - on a nonlinear force the two methods differ in the h^3 term of the
//     velocity, by Taylor expansion (also derived in the handout).
#pragma once
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "heldout.h"
#include "test_helpers.h"
#include "wb/dynamics.h"

namespace mptest {

using wb::Mat2X;
using wb::StepFn;

// Work arrays of the right size, filled with NaN: a step must write a work
// array before it reads it (their contents on entry are undefined).
// A number as a reader would write it (0.1, not 0.100000).
inline std::string num(double x) {
  std::ostringstream o;
  o << x;
  return o.str();
}

inline wb::Scratch nan_scratch(Eigen::Index n) {
  wb::Scratch s;
  s.resize(n);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (Mat2X* m : {&s.a0, &s.a1, &s.a2, &s.a3, &s.x1, &s.v1, &s.xs, &s.vs}) m->setConstant(nan);
  return s;
}

// ---------------------------------------------------------------------------
// Order of accuracy on the circular Kepler orbit.
//
// a(x) = -x / |x|^3 (GM = 1); from x = (1, 0), v = (0, 1) the exact motion is
// x(t) = (cos t, sin t), v(t) = (-sin t, cos t): a nonlinear force with a
// closed-form answer. The error at T after N steps of h = T/N behaves like
// e = C h^2 (1 + D h + ...), so the measured order log2(e(h) / e(h/2)) is
// 2 + O(h). Step sizes: see kOrderSteps.

constexpr double kOrderT = 2.0;  // end time (s): about a third of a turn
// N = 80 ... 640 (h = 0.025 ... 0.003125): in the asymptotic range. The O(h)
// drift of the measured order is at most 0.007 here (trapezoid, 80 -> 160
// steps; about 0.03 at h = 0.05 and 0.3 at h = 0.4, halving with h), and
// rounding adds about N 1e-16 to errors of 1e-5 or more.
const std::vector<int> kOrderSteps = {80, 160, 320, 640};
// Window around 2: wide enough for the O(h) drift above (< 0.01), narrow
// enough that a first-order method (order 1) or an inconsistent one (order 0)
// cannot pass, and that a third-order result would also be flagged.
constexpr double kOrderWindow = 0.1;

inline double kepler_error(StepFn step, int N) {
  wb::LambdaDynamics dyn([](const Mat2X& x, const Mat2X&, Mat2X& a) {
    for (Eigen::Index i = 0; i < x.cols(); ++i) {
      const double r = x.col(i).norm();
      a.col(i) = -x.col(i) / (r * r * r);
    }
  });
  Mat2X x(2, 1), v(2, 1);
  x << 1.0, 0.0;
  v << 0.0, 1.0;
  wb::Scratch s = nan_scratch(1);
  const double h = kOrderT / N;
  for (int k = 0; k < N; ++k) step(dyn, h, x, v, s);
  const wb::Vec2 xe(std::cos(kOrderT), std::sin(kOrderT)),
      ve(-std::sin(kOrderT), std::cos(kOrderT));
  const double ex = (wb::Vec2(x.col(0)) - xe).norm(), ev = (wb::Vec2(v.col(0)) - ve).norm();
  return std::sqrt(ex * ex + ev * ev);  // NaN stays NaN and fails below
}

inline void check_second_order(StepFn step, const std::string& method) {
  std::vector<double> e;
  for (int N : kOrderSteps) e.push_back(kepler_error(step, N));
  for (std::size_t k = 0; k + 1 < e.size(); ++k) {
    const double p = std::log2(e[k] / e[k + 1]);
    INFO(method << " on the circular Kepler orbit, T = " << kOrderT << ": error " << e[k]
                << " with " << kOrderSteps[k] << " steps, " << e[k + 1] << " with "
                << kOrderSteps[k + 1] << " steps\n  measured order log2(ratio) = " << p
                << ", expected 2 +- " << kOrderWindow
                << " (a second-order method: halving h divides the error by 4).\n"
                << "  Order near 1: a stage is first order (half step taken as a full one,\n"
                << "  an old velocity or acceleration). Order near 0: the step is not\n"
                << "  even consistent (it does not move by h f(X) to first order).");
    REQUIRE(std::isfinite(p));
    REQUIRE(std::abs(wbtest::finite(p) - 2.0) <= kOrderWindow);
  }
}

// ---------------------------------------------------------------------------
// Linear forces: one step is exactly I + hA + (hA)^2/2.

// Rounding: a step is a dozen floating-point operations on O(1) numbers, so
// the result carries a few units of 2.2e-16; 1e-13 leaves a margin of ~100.
constexpr double kRoundTol = 1e-13;

// Per particle i and coordinate: a = -k_i x - c_i v (mass 1), so the state
// (x, v) of each coordinate obeys X' = A X with A = [[0, 1], [-k_i, -c_i]].
inline wb::LambdaDynamics linear_dynamics(const std::vector<double>& k,
                                          const std::vector<double>& c) {
  return wb::LambdaDynamics([k, c](const Mat2X& x, const Mat2X& v, Mat2X& a) {
    for (Eigen::Index i = 0; i < x.cols(); ++i) a.col(i) = -k[i] * x.col(i) - c[i] * v.col(i);
  });
}

// The exact one-step result of a second-order Runge-Kutta method on X' = A X:
// M X with M = I + hA + (hA)^2/2 (both methods, see the handout).
inline void linear_step_expected(double k, double c, double h, const wb::Vec2& x,
                                 const wb::Vec2& v, wb::Vec2& x1, wb::Vec2& v1) {
  Eigen::Matrix2d A;
  A << 0.0, 1.0, -k, -c;
  const Eigen::Matrix2d M = Eigen::Matrix2d::Identity() + h * A + 0.5 * h * h * A * A;
  for (int d = 0; d < 2; ++d) {  // each coordinate separately: (x_d, v_d)
    const Eigen::Vector2d X1 = M * Eigen::Vector2d(x[d], v[d]);
    x1[d] = X1[0];
    v1[d] = X1[1];
  }
}

// The undamped oscillator: E_{n+1} / E_n = 1 + (h w)^4 / 4 at every step, and
// a damped one: one step equals M X. Several particles at once, each with its
// own constants, so that a step that mixes columns is caught too.
inline void check_linear_step(StepFn step, const std::string& method,
                              const std::vector<double>& k, const std::vector<double>& c,
                              double h, const Mat2X& x0, const Mat2X& v0) {
  wb::LambdaDynamics dyn = linear_dynamics(k, c);
  Mat2X x = x0, v = v0;
  wb::Scratch s = nan_scratch(x.cols());
  step(dyn, h, x, v, s);
  Mat2X xe(2, x0.cols()), ve(2, x0.cols());
  for (Eigen::Index i = 0; i < x0.cols(); ++i) {
    wb::Vec2 x1, v1;
    linear_step_expected(k[i], c[i], h, x0.col(i), v0.col(i), x1, v1);
    xe.col(i) = x1;
    ve.col(i) = v1;
  }
  const std::string law = method + ", one step of h = " + num(h) +
                          " on a = -k x - c v: the lecture's method gives (I + hA + (hA)^2/2) X";
  wbtest::require_near(x, xe, kRoundTol, law + " (positions)", kRoundTol);
  wbtest::require_near(v, ve, kRoundTol, law + " (velocities)", kRoundTol);
}

// One particle on a damped spring (k = 4, c = 0.7), one step of h = 0.3 (check_linear_step).
inline void check_damped_spring_step(StepFn step, const std::string& method) {
  Mat2X x(2, 1), v(2, 1);
  x << 0.6, -0.25;
  v << -0.9, 1.3;
  check_linear_step(step, method, {4.0}, {0.7}, 0.3, x, v);
}

// Three particles, each with its own spring and damper: particle i must come out as if it
// were stepped alone (check_linear_step).
inline void check_columns_apart(StepFn step, const std::string& method) {
  Mat2X x(2, 3), v(2, 3);
  x << 1.0, -0.5, 0.2, 0.3, 0.8, -1.4;
  v << 0.0, 2.0, -0.6, -1.0, 0.1, 0.9;
  check_linear_step(step, method, {1.0, 25.0, 4.0}, {0.0, 0.5, 2.0}, 0.1, x, v);
}

inline void check_energy_factor(StepFn step, const std::string& method) {
  const double w = 3.0;  // rad/s, so k = w^2 with m = 1
  for (double z : {0.1, 0.5, 1.0, 2.0}) {
    const double h = z / w;
    wb::LambdaDynamics dyn = linear_dynamics({w * w}, {0.0});
    Mat2X x(2, 1), v(2, 1);
    x << 0.3, -0.8;
    v << 1.1, 0.4;
    wb::Scratch s = nan_scratch(1);
    auto E = [&] { return 0.5 * v.squaredNorm() + 0.5 * w * w * x.squaredNorm(); };
    const double factor = 1.0 + z * z * z * z / 4.0;
    for (int n = 0; n < 5; ++n) {
      const double e0 = E();
      step(dyn, h, x, v, s);
      wbtest::require_near(E() / e0, factor, 0.0,
                           method + " on the oscillator a = -w^2 x, h w = " + num(z) + ", step " +
                               std::to_string(n + 1) +
                               ": energy ratio E_n+1 / E_n must be exactly 1 + (h w)^4 / 4",
                           kRoundTol);
    }
  }
}

// ---------------------------------------------------------------------------
// The h^3 term on a nonlinear force: where midpoint and trapezoid differ.
//
// Per coordinate, a pendulum with cubic air drag: a(x, v) = -sin x - b v^3.
// With f = (v, a0), Taylor expansion of one step from (x, v) gives
//   positions: x' = x + h v + h^2/2 a0                      exactly, both methods
//   velocities: v' = T2 + coef h^3 a''[f, f] + O(h^4),
//     T2 = v + h a0 + h^2/2 (a_x v + a_v a0)                 (the exact 2nd-order Taylor step)
//     a''[f, f] = a_xx v^2 + 2 a_xv v a0 + a_vv a0^2 = sin(x) v^2 - 6 b v a0^2
//     coef = 1/8 for the midpoint method, 1/4 for the trapezoid method
// (the exact motion has h^3/6 (a''[f, f] + the J J f term): neither method
// gets the h^3 term right, and they miss it by different amounts).

constexpr double kDrag = 0.5;  // b (1/(m s)): makes a depend on v nonlinearly
// Measured coef: (v' - T2) / (h^3 a''[f, f]) at h = 4e-3, 2e-3, 1e-3. The
// O(h^4) term shifts it by O(h) relative (below 0.3% at h = 4e-3 for these
// O(1) derivatives), rounding by about 1e-16 / h^3 <= 1e-7: a 5% window
// separates 1/8 from 1/4 by a factor 20, and any first-order slip makes
// (v' - T2) / h^3 grow like 1/h.
constexpr double kTermH = 1e-3;
constexpr double kTermRelTol = 0.05;

inline void check_third_order_term(StepFn step, const std::string& method, double coef) {
  wb::LambdaDynamics dyn([](const Mat2X& x, const Mat2X& v, Mat2X& a) {
    a = -x.array().sin() - kDrag * v.array().cube();
  });
  Mat2X x0(2, 1), v0(2, 1);
  x0 << 0.7, -1.1;
  v0 << 0.4, 0.9;
  for (double h : {4 * kTermH, 2 * kTermH, kTermH}) {
    Mat2X x = x0, v = v0;
    wb::Scratch s = nan_scratch(1);
    step(dyn, h, x, v, s);
    for (int d = 0; d < 2; ++d) {
      const double xd = x0(d, 0), vd = v0(d, 0);
      const double a0 = -std::sin(xd) - kDrag * vd * vd * vd;
      const double ax = -std::cos(xd), av = -3.0 * kDrag * vd * vd;
      const double T2 = vd + h * a0 + 0.5 * h * h * (ax * vd + av * a0);
      const double d2a = std::sin(xd) * vd * vd - 6.0 * kDrag * vd * a0 * a0;
      const std::string where = method + ", one step of h = " + num(h) +
                                " on a = -sin x - b v^3, coordinate " + std::to_string(d);
      wbtest::require_near(x(d, 0), xd + h * vd + 0.5 * h * h * a0, kRoundTol,
                           where + ": the position must be x + h v + h^2/2 a(x, v) exactly");
      const double measured = (v(d, 0) - T2) / (h * h * h * d2a);
      wbtest::require_near(measured, coef, 0.0,
                           where + ": (v' - Taylor 2nd order step) / (h^3 a''[f,f]) must be " +
                               num(coef) +
                               " (the h^3 term that makes this method differ from the other one)",
                           kTermRelTol);
    }
  }
}

// ---------------------------------------------------------------------------
// Exactly two force evaluations per step.

inline void check_two_evaluations(StepFn step, const std::string& method) {
  wb::LambdaDynamics dyn = linear_dynamics({4.0, 9.0}, {0.1, 0.0});
  Mat2X x(2, 2), v(2, 2);
  x << 1.0, 0.5, -0.2, 0.3;
  v << 0.0, -1.0, 0.4, 0.2;
  wb::Scratch s = nan_scratch(2);
  for (int n = 1; n <= 3; ++n) {
    const long before = dyn.evals();
    step(dyn, 0.01, x, v, s);
    INFO(method << ", step " << n
                << ": expected exactly 2 calls to dyn.acceleration per step, got "
                << dyn.evals() - before
                << " (one at the start, one at the intermediate state; no more, no fewer)");
    REQUIRE(dyn.evals() - before == 2);
  }
}

// ---------------------------------------------------------------------------
// The held-out check (tests/common/heldout.h): systems the student has never seen (1 to 7
// particles, a random nonlinear a(x, v), a random step size), every step compared with the
// method's definition, each of its two force evaluations at the state the definition says:
//   midpoint:  a0 = a(x, v); (xm, vm) = (x + h/2 v, v + h/2 a0); a1 = a(xm, vm);
//              x' = x + h vm, v' = v + h a1
//   trapezoid: a0 = a(x, v); (xa, va) = (x + h v, v + h a0); a1 = a(xa, va);
//              x' = x + h/2 (v + va), v' = v + h/2 (a0 + a1)
inline void check_random_steps(wbtest::HeldOut& g, StepFn step, bool trapezoid,
                               const std::string& method) {
  for (Eigen::Index n : {Eigen::Index(g.integer(3, 7)), Eigen::Index(1)}) {
    const auto accel = wbtest::random_accel(g, n);  // a random nonlinear a(x, v)
    std::vector<Mat2X> seen_x, seen_v;
    wb::LambdaDynamics dyn([&](const Mat2X& x, const Mat2X& v, Mat2X& a) {
      seen_x.push_back(x), seen_v.push_back(v);
      accel(x, v, a);
    });
    const double h = g.log_uniform(1e-3, 0.3);
    Mat2X x = g.points(n, -4.0, 4.0), v = g.points(n, -4.0, 4.0);
    INFO(method << ", " << n << " particles, h = " << h);
    for (int k = 1; k <= 3; ++k) {
      const Mat2X xn = x, vn = v;
      Mat2X a0(2, n), a1(2, n);
      accel(xn, vn, a0);
      const Mat2X x1 = xn + (trapezoid ? h : 0.5 * h) * vn,
                  v1 = vn + (trapezoid ? h : 0.5 * h) * a0;
      accel(x1, v1, a1);
      const Mat2X xe = trapezoid ? Mat2X(xn + 0.5 * h * (vn + v1)) : Mat2X(xn + h * v1);
      const Mat2X ve = trapezoid ? Mat2X(vn + 0.5 * h * (a0 + a1)) : Mat2X(vn + h * a1);
      seen_x.clear(), seen_v.clear();
      wb::Scratch s = nan_scratch(n);
      step(dyn, h, x, v, s);
      INFO("step " << k << " from x = " << wbtest::text(xn) << ", v = " << wbtest::text(vn));
      {
        INFO("force evaluations in this step: expected 2, got " << seen_x.size());
        REQUIRE(seen_x.size() == 2);
      }
      // Each value is a few roundings of terms of at most ~10^3: 1e-11 absolute is ample for
      // any order of the same operations.
      wbtest::require_near(seen_x[0], xn, 0.0, "the first evaluation sees the positions x_n");
      wbtest::require_near(seen_v[0], vn, 0.0, "the first evaluation sees the velocities v_n");
      const std::string mid = trapezoid ? "the full Euler step X_a = X + h f(X)"
                                        : "the half Euler step X_mid = X + (h/2) f(X)";
      wbtest::require_near(seen_x[1], x1, 1e-11,
                           "the second evaluation sees the positions of " + mid, 1e-12);
      wbtest::require_near(seen_v[1], v1, 1e-11,
                           "the second evaluation sees the velocities of " + mid, 1e-12);
      wbtest::require_near(
          x, xe, 1e-11, method + (trapezoid ? ": x' = x + h/2 (v + v_a)" : ": x' = x + h v_mid"),
          1e-12);
      wbtest::require_near(
          v, ve, 1e-11,
          method + (trapezoid ? ": v' = v + h/2 (a(X) + a(X_a))" : ": v' = v + h a(X_mid)"),
          1e-12);
    }
  }
}

}  // namespace mptest
