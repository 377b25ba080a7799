// Graded tests for M2, the trapezoid method (labs/midpoint/trapezoid.cpp). The checks
// themselves, and where each expected value comes from, are in second_order_checks.h: what
// stays alike in M1's and M2's files is each task's list of test cases, its names, tags and
// points (docs/contributor.md, "Repeated code").
#include "second_order_checks.h"
#include "trapezoid.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_M2_trapezoid {

namespace {
const char* kMethod = "trapezoid";
constexpr double kThirdOrderCoef = 1.0 / 4.0;  // h^3 a''[f, f] coefficient (Taylor expansion)
}  // namespace

TEST_CASE("M2 trapezoid: second order on the circular Kepler orbit", "[midpoint][M2][12pts]") {
  mptest::check_second_order(wbtest::Params(), trapezoid_step, kMethod);
}

TEST_CASE("M2 trapezoid: oscillator energy grows by 1 + (h w)^4/4 per step",
          "[midpoint][M2][8pts]") {
  mptest::check_energy_factor(wbtest::Params(), trapezoid_step, kMethod);
}

TEST_CASE("M2 trapezoid: one step on a damped spring is (I + hA + (hA)^2/2) X",
          "[midpoint][M2][7pts]") {
  mptest::check_damped_spring_step(wbtest::Params(), trapezoid_step, kMethod);
}

TEST_CASE("M2 trapezoid: several particles at once without mixing columns",
          "[midpoint][M2][5pts]") {
  mptest::check_columns_apart(wbtest::Params(), trapezoid_step, kMethod);
}

TEST_CASE("M2 trapezoid: h^3 velocity term on a nonlinear force is one quarter of a''(f f)",
          "[midpoint][M2][7pts]") {
  mptest::check_third_order_term(wbtest::Params(), trapezoid_step, kMethod, kThirdOrderCoef);
}

TEST_CASE("M2 trapezoid: exactly two force evaluations per step", "[midpoint][M2][3pts]") {
  mptest::check_two_evaluations(wbtest::Params(), trapezoid_step, kMethod);
}

// The public scenarios again with drawn parameters, after random systems (second_order_checks.h).
TEST_CASE(
    "M2 held-out: every step of random systems follows the trapezoid rule with its two "
    "evaluations",
    "[midpoint][M2][held-out][8pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("M2")) {
    INFO(g.replay());
    mptest::check_held_out(g, trapezoid_step, true, kMethod, kThirdOrderCoef);
  }
}

}  // namespace test_M2_trapezoid
