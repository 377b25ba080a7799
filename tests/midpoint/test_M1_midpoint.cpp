// Graded tests for M1, the midpoint method (labs/midpoint/midpoint.cpp). The checks
// themselves, and where each expected value comes from, are in second_order_checks.h: what
// stays alike in M1's and M2's files is each task's list of test cases, its names, tags and
// points (docs/contributor.md, "Repeated code").
#include "midpoint.h"
#include "second_order_checks.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_M1_midpoint {

namespace {
const char* kMethod = "midpoint";
constexpr double kThirdOrderCoef = 1.0 / 8.0;  // h^3 a''[f, f] coefficient (Taylor expansion)
}  // namespace

TEST_CASE("M1 midpoint: second order on the circular Kepler orbit", "[midpoint][M1][12pts]") {
  mptest::check_second_order(wbtest::Params(), midpoint_step, kMethod);
}

TEST_CASE("M1 midpoint: oscillator energy grows by 1 + (h w)^4/4 per step",
          "[midpoint][M1][8pts]") {
  mptest::check_energy_factor(wbtest::Params(), midpoint_step, kMethod);
}

TEST_CASE("M1 midpoint: one step on a damped spring is (I + hA + (hA)^2/2) X",
          "[midpoint][M1][7pts]") {
  mptest::check_damped_spring_step(wbtest::Params(), midpoint_step, kMethod);
}

TEST_CASE("M1 midpoint: several particles at once without mixing columns",
          "[midpoint][M1][5pts]") {
  mptest::check_columns_apart(wbtest::Params(), midpoint_step, kMethod);
}

TEST_CASE("M1 midpoint: h^3 velocity term on a nonlinear force is one eighth of a''(f f)",
          "[midpoint][M1][7pts]") {
  mptest::check_third_order_term(wbtest::Params(), midpoint_step, kMethod, kThirdOrderCoef);
}

TEST_CASE("M1 midpoint: exactly two force evaluations per step", "[midpoint][M1][3pts]") {
  mptest::check_two_evaluations(wbtest::Params(), midpoint_step, kMethod);
}

// The public scenarios again with drawn parameters, after random systems (second_order_checks.h).
TEST_CASE(
    "M1 held-out: every step of random systems follows the midpoint rule with its two "
    "evaluations",
    "[midpoint][M1][held-out][8pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("M1")) {
    INFO(g.replay());
    mptest::check_held_out(g, midpoint_step, false, kMethod, kThirdOrderCoef);
  }
}

}  // namespace test_M1_midpoint
