// Graded tests for TODO(D1), Heun's step (labs/drag/heun_drag.cpp): the throwaway lab of
// tools/newlab-check. Expected values come from the step's definition and, under linear
// drag a = -b v, its closed form: v' = (1 - bh + (bh)^2/2) v, x' = x + h (1 - bh/2) v.
#include <cmath>
#include <limits>

#include "heldout.h"
#include "heun_drag.h"
#include "test_helpers.h"

namespace test_D1_heun_drag {

using wb::Mat2X;
using wbtest::require_near;

namespace {

// One step is a handful of multiplications and additions: a few ulps of the largest term.
constexpr double kStepTol = 1e-13;

// One Heun step of `dyn` from (x, v), with work arrays full of NaN (undefined on entry).
void step(const wb::Dynamics& dyn, double h, Mat2X& x, Mat2X& v) {
  wb::Scratch s;
  s.resize(x.cols());
  for (Mat2X* m : {&s.a0, &s.a1, &s.a2, &s.a3, &s.x1, &s.v1, &s.xs, &s.vs})
    m->setConstant(std::numeric_limits<double>::quiet_NaN());
  heun_step(dyn, h, x, v, s);
}

wb::LambdaDynamics drag(double b) {
  return wb::LambdaDynamics([b](const Mat2X&, const Mat2X& v, Mat2X& a) { a = -b * v; });
}

void check_drag_step(double b, double h, const Mat2X& x0, const Mat2X& v0) {
  Mat2X x = x0, v = v0;
  step(drag(b), h, x, v);
  const double bh = b * h;
  require_near(v, Mat2X((1.0 - bh + 0.5 * bh * bh) * v0), kStepTol,
               "Heun under drag: v' = (1 - bh + (bh)^2/2) v (the average of the two slopes)",
               kStepTol);
  require_near(x, Mat2X(x0 + h * (1.0 - 0.5 * bh) * v0), kStepTol,
               "Heun under drag: x' = x + h (v + v1)/2 = x + h (1 - bh/2) v", kStepTol);
}

}  // namespace

TEST_CASE("D1 one step under linear drag: v' = (1 - bh + (bh)^2/2) v", "[drag][D1][45pts]") {
  Mat2X x0(2, 2), v0(2, 2);
  x0 << 1.0, -2.0, 0.5, 3.0;
  v0 << 2.0, -1.5, 0.25, 4.0;
  check_drag_step(0.8, 0.125, x0, v0);
}

TEST_CASE("D1 two force evaluations per step with the second at the Euler predictor",
          "[drag][D1][40pts]") {
  // a(x, v) = (x_y, -v_x): the second slope is taken at x1 = x + h v, v1 = v + h a0.
  wb::LambdaDynamics dyn([](const Mat2X& x, const Mat2X& v, Mat2X& a) {
    a.row(0) = x.row(1);
    a.row(1) = -v.row(0);
  });
  Mat2X x0(2, 1), v0(2, 1);
  x0 << 0.5, -1.0;
  v0 << 2.0, 0.75;
  const double h = 0.25;
  Mat2X a0(2, 1), a1(2, 1);
  a0 << x0(1, 0), -v0(0, 0);
  const Mat2X x1 = x0 + h * v0, v1 = v0 + h * a0;
  a1 << x1(1, 0), -v1(0, 0);
  Mat2X x = x0, v = v0;
  step(dyn, h, x, v);
  {
    INFO("force evaluations in one Heun step: expected 2, got " << dyn.evals());
    REQUIRE(dyn.evals() == 2);
  }
  require_near(v, Mat2X(v0 + 0.5 * h * (a0 + a1)), kStepTol, "v' = v + h/2 (a(x, v) + a(x1, v1))",
               kStepTol);
  require_near(x, Mat2X(x0 + 0.5 * h * (v0 + v1)), kStepTol, "x' = x + h/2 (v + v1)", kStepTol);
}

TEST_CASE("D1 held-out: random drag steps follow the closed form",
          "[drag][D1][held-out][15pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("D1")) {
    INFO(g.replay());
    const double b = g.log_uniform(0.01, 10.0), h = g.log_uniform(1e-3, 0.5);
    const Eigen::Index n = g.integer(1, 5);
    check_drag_step(b, h, g.points(n, -10.0, 10.0), g.points(n, -5.0, 5.0));
  }
}

}  // namespace test_D1_heun_drag
