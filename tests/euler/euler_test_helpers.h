// Test-written dynamics and a stepping loop for the euler lab's graded tests.
// Nothing here uses the forces lab: every acceleration is written in the test.
#pragma once
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "heldout.h"
#include "params.h"
#include "test_helpers.h"
#include "wb/dynamics.h"

namespace eulertest {

using wb::Mat2X;
using wb::Vec2;

// Runs one step function on a state, with a scratch that holds NaN on entry to
// every step (its contents are undefined: a step must write before it reads).
// Records the state each force evaluation saw.
struct Run {
  wb::LambdaDynamics dyn;
  Mat2X x, v;
  wb::Scratch s;
  std::vector<Mat2X> seen_x, seen_v;  // the arguments of every evaluation, if recording
  bool record = false;

  Run(wb::LambdaDynamics::Fn accel, const Mat2X& x0, const Mat2X& v0)
      : dyn([this, accel](const Mat2X& xx, const Mat2X& vv, Mat2X& a) {
          if (record) seen_x.push_back(xx), seen_v.push_back(vv);
          accel(xx, vv, a);
        }),
        x(x0),
        v(v0) {
    s.resize(x0.cols());
  }
  Run(const Run&) = delete;  // dyn refers to this object
  Run& operator=(const Run&) = delete;

  void step(wb::StepFn fn, double h) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    for (Mat2X* m : {&s.a0, &s.a1, &s.a2, &s.a3, &s.x1, &s.v1, &s.xs, &s.vs}) m->setConstant(nan);
    fn(dyn, h, x, v, s);
  }
};

// a_i = -w^2 x_i for every particle: a harmonic oscillator about the origin
// (a zero-rest-length spring to an anchor at the origin, k / m = w^2).
inline wb::LambdaDynamics::Fn oscillator(double w) {
  return [w](const Mat2X& x, const Mat2X&, Mat2X& a) { a = -(w * w) * x; };
}

// E = 1/2 m |v|^2 + 1/2 k |x|^2, summed over particles of mass m, stiffness k.
inline double oscillator_energy(const Mat2X& x, const Mat2X& v, double m, double k) {
  return 0.5 * m * v.squaredNorm() + 0.5 * k * x.squaredNorm();
}

// a = -GM x / |x|^3: a point attractor of strength GM at the origin.
inline wb::LambdaDynamics::Fn attractor(double GM) {
  return [GM](const Mat2X& x, const Mat2X&, Mat2X& a) {
    for (Eigen::Index i = 0; i < x.cols(); ++i) {
      const double r = x.col(i).norm();
      a.col(i) = -GM / (r * r * r) * x.col(i);
    }
  };
}

inline Mat2X cols(std::initializer_list<Vec2> list) {
  Mat2X m(2, Eigen::Index(list.size()));
  Eigen::Index i = 0;
  for (const Vec2& c : list) m.col(i++) = c;
  return m;
}

// The one-step case of E1 and E2: three particles under accelerations that depend on x and
// v, different for every particle, one step of h from (x0, v0); a0 = a(x0, v0), the one
// evaluation either method makes. Held-out (wbtest::Params): 2 to 4 particles, every
// coefficient, coordinate and h drawn in the published ones' ranges.
struct OneStep {
  Eigen::Index n;
  Mat2X x0, v0;
  double h;
  Mat2X a0;
  wb::LambdaDynamics::Fn accel;
  explicit OneStep(const wbtest::Params& p)
      : n(p.count(3, 2, 4)), x0(2, n), v0(2, n), h(p.num(0.25, 0.1, 0.4)), a0(2, n) {
    // a_i = (c0 x_i.x + c1 v_i.y + c2 + i, c3 x_i.y x_i.x + c4 v_i.x + c5 i)
    const std::array<double, 6> c = {p.num(-3.0, -4.0, -1.0), p.num(0.5, 0.1, 1.0),
                                     p.num(1.0, -2.0, 2.0),   p.num(2.0, 0.5, 3.0),
                                     p.num(-0.25, -1.0, 1.0), p.num(-0.5, -1.0, 1.0)};
    accel = [c](const Mat2X& x, const Mat2X& v, Mat2X& a) {
      for (Eigen::Index i = 0; i < x.cols(); ++i) {
        a.col(i) = Vec2(c[0] * x(0, i) + c[1] * v(1, i) + c[2] + double(i),
                        c[3] * x(1, i) * x(0, i) + c[4] * v(0, i) + c[5] * double(i));
      }
    };
    const Mat2X px = cols({{1.0, 2.0}, {-0.5, 0.25}, {3.0, -1.5}});
    const Mat2X pv = cols({{0.5, -1.0}, {2.0, 0.75}, {-1.25, 0.125}});
    for (Eigen::Index i = 0; i < n; ++i) {
      for (int d = 0; d < 2; ++d) {
        x0(d, i) = p.num(i < 3 ? px(d, i) : 0.0, -3.0, 3.0);
        v0(d, i) = p.num(i < 3 ? pv(d, i) : 0.0, -2.0, 2.0);
      }
    }
    accel(x0, v0, a0);
  }
};

// Checks that `step` makes exactly one force evaluation per step, at the state
// (x_n, v_n) the step started from; `method` names it in failure messages.
// Held-out: 1 to 3 particles, w, h and the start drawn; as many steps.
inline void check_one_evaluation_at_start(const wbtest::Params& p, wb::StepFn step,
                                          const std::string& method) {
  const Eigen::Index particles = p.count(2, 1, 3);
  const Mat2X px = cols({{1.0, 0.5}, {-2.0, 0.0}}), pv = cols({{0.0, 1.0}, {0.5, 0.5}});
  Mat2X x0(2, particles), v0(2, particles);
  for (Eigen::Index i = 0; i < particles; ++i) {
    for (int d = 0; d < 2; ++d) {
      x0(d, i) = p.num(i < 2 ? px(d, i) : 0.0, -2.0, 2.0);
      v0(d, i) = p.num(i < 2 ? pv(d, i) : 0.0, -1.0, 1.0);
    }
  }
  const double w = p.num(3.0, 2.0, 4.0), h = p.num(0.05, 0.02, 0.08);
  Run r(oscillator(w), x0, v0);
  r.record = true;
  for (int n = 0; n < 25; ++n) {
    const Mat2X xn = r.x, vn = r.v;
    const std::size_t before = r.seen_x.size();
    r.step(step, h);
    INFO(method << ", step " << n + 1);
    {
      INFO("force evaluations in this step: expected 1, got " << r.seen_x.size() - before);
      REQUIRE(r.seen_x.size() == before + 1);
    }
    wbtest::require_near(r.seen_x.back(), xn, 0.0, "the evaluation must see the positions x_n");
    wbtest::require_near(r.seen_v.back(), vn, 0.0, "the evaluation must see the velocities v_n");
  }
  INFO("Dynamics::evals() after 25 steps");
  REQUIRE(r.dyn.evals() == 25);
}

// Six particles, particle i an oscillator with its own w_i. Per coordinate a
// step is the linear map (x, v) -> M(h, w_i) (x, v), so after N steps each
// column must equal M^N (x0, v0) of its own particle: a step that mixes
// columns, or skips some, fails. `M` is written out in `matrix_text`. Held-out: 5 to 7
// particles, each w_i, h and the start drawn (h w_i at most 0.3, as published); as many steps.
inline void check_independent_particles(const wbtest::Params& p, wb::StepFn step,
                                        const std::function<wb::Mat2(double h, double w)>& M,
                                        const std::string& matrix_text) {
  const Eigen::Index n = p.count(6, 5, 7);
  const double h = p.num(0.02, 0.015, 0.025);
  const double published_w[6] = {1.0, 2.0, 3.5, 5.0, 8.0, 13.0};
  Eigen::VectorXd w(n);
  for (Eigen::Index i = 0; i < n; ++i) w[i] = p.num(i < 6 ? published_w[i] : 0.0, 0.5, 12.0);
  auto accel = [&](const Mat2X& x, const Mat2X&, Mat2X& a) {
    for (Eigen::Index i = 0; i < x.cols(); ++i) a.col(i) = -(w[i] * w[i]) * x.col(i);
  };
  Mat2X x0(2, n), v0(2, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    x0.col(i) = Vec2(p.num(1.0 + 0.5 * double(i), 1.0, 4.0), p.num(-0.25 * double(i), -1.5, 0.0));
    v0.col(i) = Vec2(p.num(0.1 * double(i), 0.0, 0.6), p.num(2.0 - 0.3 * double(i), 0.5, 2.0));
  }
  const int N = 100;
  Run r(accel, x0, v0);
  for (int k = 0; k < N; ++k) r.step(step, h);
  for (Eigen::Index i = 0; i < n; ++i) {
    wb::Mat2 P = wb::Mat2::Identity();
    for (int k = 0; k < N; ++k) P = M(h, w[i]) * P;
    for (int d = 0; d < 2; ++d) {
      const Vec2 e = P * Vec2(x0(d, i), v0(d, i));
      INFO("particle " << i << " (w = " << w[i] << "), coordinate " << d
                       << ": every column must be stepped with its own state only");
      wbtest::require_near(Vec2(r.x(d, i), r.v(d, i)), e, 1e-12,
                           "(x, v) after 100 steps = M^100 (x0, v0), M = " + matrix_text, 1e-10);
    }
  }
}

// Free fall, a = g, three particles, 1000 steps of h = 0.01: v_n = v0 + g t_n exactly, and
// x_n = x0 + v0 t_n + 1/2 g t_n^2 -+ 1/2 g h t_n, the last term's sign the method's
// (explicit, velocity_first false: -, semi-implicit: +; each test derives its own).
// Held-out: 3 particles (a count drawn around 3 would make 2 and 4 particle calls, rare among
// the public tests', tell the held-out test apart), g, h and the start drawn; 300 steps (the
// share of calls the public test has among its task's, as tools/adversary --inputs samples them)
// of a larger h, so that the run lasts about as long and reaches the same magnitudes.
inline void check_free_fall(const wbtest::Params& p, wb::StepFn step, bool velocity_first,
                            const std::string& method) {
  const Vec2 g(p.num(0.3, -1.0, 1.0), p.num(-9.81, -12.0, -5.0));
  auto accel = [g](const Mat2X& x, const Mat2X&, Mat2X& a) { a = g.replicate(1, x.cols()); };
  Mat2X x0 = cols({{0.0, 100.0}, {5.0, 0.0}, {-2.0, 40.0}});
  Mat2X v0 = cols({{1.0, 0.0}, {0.0, 20.0}, {-3.0, 7.5}});
  for (Eigen::Index i = 0; i < 3; ++i) {
    x0.col(i) = Vec2(p.num(x0(0, i), -5.0, 5.0), p.num(x0(1, i), 0.0, 100.0));
    v0.col(i) = Vec2(p.num(v0(0, i), -3.0, 3.0), p.num(v0(1, i), 0.0, 20.0));
  }
  const double h = p.num(0.01, 0.025, 0.04);
  const double half = velocity_first ? 0.5 : -0.5;  // the sign of the 1/2 g h t term
  const std::string law =
      method + " free fall x0 + v0 t + g t^2/2 " + (velocity_first ? "+" : "-") + " g h t/2";
  Run r(accel, x0, v0);
  const long steps = p.steps(1000, 300);
  for (long n = 1; n <= steps; ++n) {
    r.step(step, h);
    const double t = n * h;
    Mat2X xe = x0 + v0 * t;
    xe.colwise() += (0.5 * t * t + half * h * t) * g;
    Mat2X ve = v0;
    ve.colwise() += t * g;
    INFO("step " << n << ", t = " << t);
    wbtest::require_near(r.x, xe, 1e-9, law, 1e-12);
    wbtest::require_near(r.v, ve, 1e-9, "free fall velocity v0 + g t", 1e-12);
  }
}

// Viscous damping, a_i = -(b / m_i) v_i, three particles of distinct masses, 60 steps:
// v_n = r_i^n v0 with r_i = 1 - h b / m_i, and x_n = x0 + h v0 c (1 - r^n) / (1 - r), where
// c = 1 for explicit Euler (velocity_first false: the old velocities v_0 ... v_{n-1}) and
// c = r for semi-implicit Euler (the new ones, v_1 ... v_n).
// Held-out: 3 particles (as check_free_fall), b, h, the masses and the start drawn (h b / m at
// most 0.15, so that 1 - r = h b / m is well away from 0 and 1); as many steps.
inline void check_damping(const wbtest::Params& p, wb::StepFn step, bool velocity_first,
                          const std::string& method) {
  const double b = p.num(0.3, 0.1, 0.5), h = p.num(0.1, 0.05, 0.15);
  Eigen::Vector3d m(0.5, 2.0, 7.0);
  Mat2X x0 = cols({{0.0, 0.0}, {1.0, -1.0}, {2.0, 3.0}});
  Mat2X v0 = cols({{4.0, -2.0}, {-1.0, 3.0}, {0.5, 6.0}});
  for (Eigen::Index i = 0; i < 3; ++i) {
    m[i] = p.num(m[i], 0.5, 8.0);
    for (int d = 0; d < 2; ++d) {
      x0(d, i) = p.num(x0(d, i), -3.0, 3.0);
      v0(d, i) = p.num(v0(d, i), -6.0, 6.0);
    }
  }
  auto accel = [&](const Mat2X&, const Mat2X& v, Mat2X& a) {
    for (Eigen::Index i = 0; i < v.cols(); ++i) a.col(i) = -(b / m[i]) * v.col(i);
  };
  Run r(accel, x0, v0);
  const int N = 60;
  for (int n = 1; n <= N; ++n) r.step(step, h);
  for (int i = 0; i < 3; ++i) {
    const double ri = 1.0 - h * b / m[i];
    const double rn = std::pow(ri, N);
    const double c = velocity_first ? h * ri : h;  // h c of the law above
    INFO("particle " << i << " of mass " << m[i]);
    wbtest::require_near(Vec2(r.v.col(i)), Vec2(rn * v0.col(i)), 1e-12,
                         method + " damping v_n = (1 - h b/m)^n v0", 1e-12);
    wbtest::require_near(Vec2(r.x.col(i)),
                         Vec2(x0.col(i) + c * (1.0 - rn) / (1.0 - ri) * v0.col(i)), 1e-12,
                         method + (velocity_first ? " damping x_n = x0 + h v0 r (1 - r^n)/(1 - r)"
                                                  : " damping x_n = x0 + h v0 (1 - r^n)/(1 - r)"),
                         1e-12);
  }
}

// One step of the method's definition on the oscillator a = -w^2 x, taken here, on the trusted
// side: the reference the long runs' checkpoints are checked against (never the lab's own step
// continuing from a state it made up: issue 42, "never check the accused with the accused").
//   explicit (velocity_first false): x' = x + h v,  v' = v - h w^2 x
//   semi-implicit (velocity_first true): v' = v - h w^2 x,  x' = x + h v'
inline void reference_oscillator_step(bool velocity_first, double w, double h, Mat2X& x,
                                      Mat2X& v) {
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const Vec2 xi = x.col(i), a = -(w * w) * xi;
    const Vec2 vi = Vec2(v.col(i)) + h * a;
    x.col(i) = xi + h * (velocity_first ? vi : Vec2(v.col(i)));
    v.col(i) = vi;
  }
}

// The checks of a long run made by euler_oscillator_run (euler_kernels.h), which runs beside
// the lab's code: the checkpoints have the promised size, start at (x0, v0), end at the final
// state, and every segment between two checkpoints is `every` steps of the method's definition,
// taken here from the first of them (reference_oscillator_step). The checkpoints are then the
// method's orbit from (x0, v0) to rounding, whatever code made them (a step that recognises its
// own made-up checkpoints, by state kept in the worker or bits hidden in the numbers, cannot
// land on the next one: the worker takes no part in the check). What the test judges is then
// computed here, from the checkpoints.
// `law(c, x, v)` checks the law the test is about at every checkpoint c (after c * every
// steps).
inline void check_long_run(bool velocity_first, double w, double h, const Mat2X& x0,
                           const Mat2X& v0, long n, long every, const Mat2X& x, const Mat2X& v,
                           const Mat2X& xs, const Mat2X& vs, const std::string& name,
                           const std::function<void(long, const Mat2X&, const Mat2X&)>& law) {
  const Eigen::Index p = x0.cols();
  const long checkpoints = n / every + 1;
  {
    INFO(name << ": the run returns " << checkpoints << " checkpoints of " << p
              << " particles, got " << xs.cols() << " and " << vs.cols() << " columns");
    REQUIRE(xs.cols() == checkpoints * p);
    REQUIRE(vs.cols() == checkpoints * p);
    REQUIRE(x.cols() == p);
    REQUIRE(v.cols() == p);
  }
  wbtest::require_finite(xs, name + ": every position of the run");
  wbtest::require_finite(vs, name + ": every velocity of the run");
  wbtest::require_near(xs.leftCols(p).eval(), x0, 0.0, name + ": the first checkpoint is x0");
  wbtest::require_near(vs.leftCols(p).eval(), v0, 0.0, name + ": the first checkpoint is v0");
  wbtest::require_near(xs.rightCols(p).eval(), x, 0.0,
                       name + ": the last checkpoint is the final x");
  wbtest::require_near(vs.rightCols(p).eval(), v, 0.0,
                       name + ": the last checkpoint is the final v");
  for (long c = 0; c < checkpoints; ++c) {
    INFO(name << ": the state after " << c * every << " steps (checkpoint " << c << ")");
    law(c, xs.middleCols(c * p, p), vs.middleCols(c * p, p));
  }
  for (long c = 0; c + 1 < checkpoints; ++c) {
    Mat2X rx = xs.middleCols(c * p, p), rv = vs.middleCols(c * p, p);
    for (long k = 0; k < every; ++k) reference_oscillator_step(velocity_first, w, h, rx, rv);
    INFO(name << ": the states between checkpoints " << c << " and " << c + 1 << " (steps "
              << c * every << " to " << (c + 1) * every
              << "), stepped by the test itself from checkpoint " << c
              << ", must be the run's checkpoint " << c + 1
              << " (the run must take every step of the method)");
    // `every` steps of rounding (~1e-16 each, relative: the oscillator's step turns and at
    // most slightly stretches the state) differ between the test's step and the lab's: below
    // 1e-13 for 1000 steps, a margin of 10.
    wbtest::require_near(rx, xs.middleCols((c + 1) * p, p).eval(), 0.0, "positions", 1e-12);
    wbtest::require_near(rv, vs.middleCols((c + 1) * p, p).eval(), 0.0, "velocities", 1e-12);
  }
}

}  // namespace eulertest
