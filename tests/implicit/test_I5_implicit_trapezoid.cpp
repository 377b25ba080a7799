// Graded tests for I5, the implicit trapezoid (labs/implicit/implicit_trapezoid.cpp;
// it uses I4). Expected values: the Cayley transform (I - hA/2)^-1 (I + hA/2)
// that the rule is on a linear system, its energy conservation, the exact
// oscillator, and the trapezoid equations themselves.
#include <Eigen/Dense>

#include "implicit_checks.h"
#include "implicit_trapezoid.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_I5_implicit_trapezoid {

namespace {
using wb::Mat2X;
using wb::Vec2;

NewtonOptions options() {
  NewtonOptions o;
  o.tol = 1e-12;
  o.max_iterations = 50;
  return o;
}
}  // namespace

TEST_CASE("I5 implicit trapezoid: energy kept exactly on linear springs at any h w",
          "[implicit][I5][3pts]") {
  // On X' = A X the step is the Cayley transform of A, which preserves the
  // energy norm: the energy ratio is 1 up to the solve's rounding (1e-9).
  SpringNetwork net =
      imtest::anchored_network({1.0, 4.0}, {9.0, 36.0}, {Vec2(0.5, 0.5), Vec2(-0.4, 0.1)});
  const double w = 3.0;
  for (double hw : {0.1, 1.0, 10.0, 1000.0}) {
    Mat2X x(2, 2), v(2, 2);
    x << 1.0, -1.2, 0.3, 0.6;
    v << 0.5, 0.4, -1.0, 0.9;
    const double E0 = imtest::energy(net, x, v);
    const Mat2X x0 = x;
    imtest::CarriedWorkspace ws;  // one per network and run
    for (int step = 0; step < 10; ++step)
      implicit_trapezoid_step(net, Mat2X::Zero(2, 2), hw / w, options(), x, v, ws.next());
    INFO("the particles must move (h w = " << hw << ")");
    REQUIRE(wbtest::finite((x - x0).norm()) > 1e-6);
    wbtest::require_near(imtest::energy(net, x, v) / E0, 1.0, 0.0,
                         "energy ratio after 10 steps at h w = " + std::to_string(hw), 1e-9);
  }
}

TEST_CASE("I5 implicit trapezoid: one step on a damped linear spring is the Cayley transform",
          "[implicit][I5][3pts]") {
  // Per coordinate X = (x - c, v), X' = A X + F with A = [[0, 1], [-k/m, -b/m]],
  // F = (0, f/m): the rule gives X' = (I - hA/2)^-1 ((I + hA/2) X + h F).
  SpringNetwork net;
  Mat2X x, v, f;
  imtest::anchored_pair(net, x, v, f);
  const double h = 0.2;
  Mat2X xe(2, 2), ve(2, 2);
  for (Eigen::Index p = 0; p < 2; ++p) {
    const double m = net.m[p], k = net.springs[p].k, b = net.drag;
    const Vec2 c = net.springs[p].anchor;
    Eigen::Matrix2d A;
    A << 0.0, 1.0, -k / m, -b / m;
    const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
    for (int d = 0; d < 2; ++d) {
      const Eigen::Vector2d X(x(d, p) - c[d], v(d, p)), F(0.0, f(d, p) / m);
      const Eigen::Vector2d X1 = imtest::solve2(I - 0.5 * h * A, (I + 0.5 * h * A) * X + h * F);
      xe(d, p) = X1[0] + c[d];
      ve(d, p) = X1[1];
    }
  }
  NewtonWorkspace ws;
  implicit_trapezoid_step(net, f, h, options(), x, v, ws);
  wbtest::require_near(x, xe, 0.0, "x' of the trapezoid rule on a linear spring", 1e-9);
  wbtest::require_near(v, ve, 0.0, "v' of the trapezoid rule on a linear spring", 1e-9);
}

TEST_CASE("I5 implicit trapezoid: second order in h against the exact oscillator",
          "[implicit][I5][2pts]") {
  // w = 2 pi, T = 0.5, N = 50 ... 200: error ~ C h^2 (1 + O((w h)^2)); a window
  // of 0.1 around 2 rejects first-order (backward Euler) and order-0 steps.
  const double w = 2.0 * M_PI, T = 0.5;
  SpringNetwork net = imtest::anchored_network({1.0}, {w * w}, {Vec2::Zero()});
  const Vec2 x0(1.0, 0.0), v0(0.0, 3.0);
  auto error = [&](int N) {
    Mat2X x = x0, v = v0;
    imtest::CarriedWorkspace ws;
    for (int s = 0; s < N; ++s)
      implicit_trapezoid_step(net, Mat2X::Zero(2, 1), T / N, options(), x, v, ws.next());
    const Vec2 xe = x0 * std::cos(w * T) + v0 / w * std::sin(w * T);
    return (Vec2(x.col(0)) - xe).norm();
  };
  double prev = error(50);
  for (int N : {100, 200}) {
    const double e = error(N), p = std::log2(prev / e);
    INFO("measured order " << p << " from " << N / 2 << " to " << N << " steps, expected 2");
    REQUIRE(std::isfinite(p));
    REQUIRE(std::abs(wbtest::finite(p) - 2.0) <= 0.1);
    prev = e;
  }
}

TEST_CASE("I5 implicit trapezoid: a pinned particle never moves even one that arrives moving",
          "[implicit][I5][2pts]") {
  SpringNetwork net;
  Mat2X x0, v0;
  imtest::small_network(net, x0, v0, 0.5, 0.1);
  net.pinned = {0, 0, 1, 0};
  // Its given velocity (0.8, -0.1) is ignored: a pinned particle has v = 0 (from
  // the start: the explicit half must not move it either).
  Mat2X f = imtest::small_network_load(false);  // gravity alone
  Mat2X x = x0, v = v0;
  imtest::CarriedWorkspace ws;
  for (int step = 0; step < 5; ++step) {
    const Mat2X xs = x, vs = v;
    implicit_trapezoid_step(net, f, 0.1, options(), x, v, ws.next());
    INFO("step " << step << ": pinned particle 2 at " << x.col(2).transpose() << ", velocity "
                 << v.col(2).transpose());
    REQUIRE(x.col(2) == x0.col(2));
    REQUIRE(v.col(2) == Vec2::Zero());
    Mat2X vp = vs;
    vp.col(2).setZero();
    const double r = imtest::trapezoid_residual(net, xs, vp, f, 0.1, x, v);
    const double s = imtest::momentum_scale(net, xs, vs, f, 0.1);
    INFO("trapezoid residual of the free particles " << r << " against scale " << s);
    REQUIRE(wbtest::finite(r) <= 1e-9 * s);
  }
}

TEST_CASE("I5 implicit trapezoid: returns the Newton report of its backward Euler half",
          "[implicit][I5][2pts]") {
  // The half step's residual M (v' - v~) - h/2 (f(x', v') + f_ext) is the
  // trapezoid's own, M (v' - v) - h/2 (f(x, v) + f(x', v')) - h f_ext.
  SpringNetwork net;
  Mat2X x0, v0;
  imtest::small_network(net, x0, v0, 0.0, 0.4);
  Mat2X f = imtest::small_network_load();
  const double h = 0.1;
  for (int cap : {1, 50}) {
    NewtonOptions o = options();
    o.max_iterations = cap;
    Mat2X x = x0, v = v0;
    NewtonWorkspace ws;
    const NewtonReport r = implicit_trapezoid_step(net, f, h, o, x, v, ws);
    Mat2X G = (v - v0) * net.m.asDiagonal() -
              0.5 * h * (imtest::forces(net, x0, v0) + imtest::forces(net, x, v)) - h * f;
    const double s = imtest::momentum_scale(net, x0, v0, f, h);
    INFO("max_iterations " << cap << ": report {iterations " << r.iterations << ", residual "
                           << r.residual << ", converged " << r.converged << ", solver_failed "
                           << r.solver_failed << "}, trapezoid residual of the returned state "
                           << G.norm() << ": return backward_euler_step's report");
    REQUIRE_FALSE(r.solver_failed);
    REQUIRE(r.iterations >= 1);         // nanfree: integers
    REQUIRE(r.iterations <= cap);       // nanfree: integers
    REQUIRE(r.converged == (cap > 1));  // nanfree: integers
    REQUIRE(wbtest::finite(r.scale) > 0.0);
    REQUIRE(wbtest::near(r.residual, G.norm(), 1e-13 * s, 1e-9));
  }
  // A failed solve (an exact zero pivot: m = (h/2)^2 k across a spring compressed to
  // half its rest length, definite = false) is reported, and the state stays finite:
  // the explicit half, then x~ + h/2 v~, v~ (the backward half's last good iterate).
  SpringNetwork bad = imtest::anchored_network({1.0}, {1.0}, {Vec2::Zero()});
  bad.springs[0].rest = 2.0;
  Mat2X x(2, 1), v = Mat2X::Zero(2, 1);
  x << 1.0, 0.0;
  NewtonOptions o = options();
  o.definite = false;
  NewtonWorkspace ws;
  const NewtonReport r = implicit_trapezoid_step(bad, Mat2X::Zero(2, 1), 2.0, o, x, v, ws);
  INFO("report {iterations " << r.iterations << ", converged " << r.converged
                             << ", solver_failed " << r.solver_failed
                             << "}: the backward half's factorisation fails, expected "
                                "solver_failed and not converged");
  REQUIRE(r.solver_failed);
  REQUIRE_FALSE(r.converged);
  wbtest::require_finite(x, "position after a failed solve");
  wbtest::require_finite(v, "velocity after a failed solve");
  // f = -k (L - rest) u = (1, 0) N: v~ = h/2 f / m = (1, 0), x' = x~ + h/2 v~ = (2, 0).
  wbtest::require_near(v, Mat2X(Vec2(1.0, 0.0)), 0.0, "v = v~ (last good iterate)", 1e-15);
  wbtest::require_near(x, Mat2X(Vec2(2.0, 0.0)), 0.0, "x = x~ + h/2 v~", 1e-15);
}

TEST_CASE("I5 held-out: random networks step by the trapezoid rule and return the Newton report",
          "[implicit][I5][held-out][3pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("I5")) {
    INFO(g.replay());
    for (int s = 0; s < 2; ++s) {
      imtest::Network w = imtest::random_network(g, true);
      const Eigen::Index n = w.net.n();
      const double h = g.log_uniform(0.005, 0.1);
      NewtonOptions o;
      o.tol = 1e-12;
      o.max_iterations = 50;
      Mat2X x = w.x, v = w.v;
      NewtonWorkspace ws;
      const NewtonReport r = implicit_trapezoid_step(w.net, w.f_ext, h, o, x, v, ws);
      // The explicit half, written here: pinned particles' v = 0 first.
      Mat2X vs = w.v;
      for (Eigen::Index p = 0; p < n; ++p)
        if (w.net.is_pinned(p)) vs.col(p).setZero();
      const Mat2X xt = w.x + 0.5 * h * vs;
      const Mat2X vt = vs + 0.5 * h * (imtest::forces(w.net, w.x, vs) + w.f_ext) *
                                w.net.m.cwiseInverse().asDiagonal();
      const double res = imtest::trapezoid_residual(w.net, w.x, vs, w.f_ext, h, x, v);
      const double scale = imtest::momentum_scale(w.net, w.x, vs, w.f_ext, h);
      const double g1 = imtest::newton_residual(w.net, xt, vt, w.f_ext, 0.5 * h, v);
      INFO(n << " particles, h = " << h << "; report {iterations " << r.iterations
             << ", residual " << r.residual << ", converged " << r.converged
             << "}; trapezoid residual " << res << " against the momentum scale " << scale
             << "; the backward Euler half's |G| at "
             << "the returned v: " << g1);
      REQUIRE(r.converged);
      REQUIRE(r.iterations >= 1);  // nanfree: integers
      REQUIRE(wbtest::finite(res) <= 1e-9 * scale);
      REQUIRE(wbtest::near(r.residual, g1, 1e-13 * scale, 1e-9));
      for (Eigen::Index p = 0; p < n; ++p) {
        if (!w.net.is_pinned(p)) continue;
        wbtest::require_near(Vec2(x.col(p)), Vec2(w.x.col(p)), 0.0,
                             "a pinned particle never moves, even one that arrives moving");
        wbtest::require_near(Vec2(v.col(p)), Vec2(0, 0), 0.0, "a pinned particle's v is 0");
      }
    }
  }
}

}  // namespace test_I5_implicit_trapezoid
