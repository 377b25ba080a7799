// The implicit lab executable: backward Euler (one spring by hand, and a
// spring network by Newton's method), the implicit trapezoid, and the explicit
// methods of the euler and midpoint labs for comparison, on the same scenes.
#include "explicit_euler.h"
#include "implicit_world.h"
#include "midpoint.h"
#include "symplectic_euler.h"
#include "trapezoid.h"
#include "wb/rk4.h"
#include "wb/run.h"

// Every lab's main has this shape: the lab's declaration (summary, integrators) handed to
// the run contract (docs/contributor.md, "Repeated code").
int main(int argc, char** argv) {
  wb::LabInfo info;
  info.lab = WB_LAB;
  info.side = WB_SIDE;
  info.summary =
      "Implicit lab: backward Euler and the implicit trapezoid on spring networks, against the "
      "explicit methods.";
  wb::Integrator rk4 = wb::rk4_integrator();
  rk4.description = "classic Runge-Kutta, provided (not a task)";
  info.integrators = {
      {"backward-euler", wb::backward_euler_adapter, 1, 1,
       "backward Euler (TODO I2-I4): Newton's method, sparse solve per iteration"},
      {"baraff-witkin", wb::baraff_witkin_adapter, 1, 1,
       "backward Euler with one linear solve (TODO I2-I4, Baraff and Witkin 1998)"},
      {"backward-euler-fast", wb::backward_euler_fast_adapter, 1, 1,
       "backward Euler, Newton: the provided fast path (your I2, assembly and solver provided)"},
      {"baraff-witkin-fast", wb::baraff_witkin_fast_adapter, 1, 1,
       "one linear solve per step: the provided fast path (your I2)"},
      {"implicit-trapezoid", wb::implicit_trapezoid_adapter, 1, 2,
       "implicit trapezoid (TODO I5): half explicit, half backward Euler"},
      {"backward-euler-1", wb::backward_euler_1_adapter, 1, 1,
       "backward Euler on one spring, solved by hand (TODO I1)", wb::backward_euler_1_check},
      {"explicit-euler", explicit_euler_step, 1, 1, "explicit Euler (euler lab, E1)"},
      {"symplectic-euler", symplectic_euler_step, 1, 1, "semi-implicit Euler (euler lab, E2)"},
      {"midpoint", midpoint_step, 2, 2, "midpoint method (midpoint lab, M1)"},
      {"trapezoid", trapezoid_step, 2, 2, "explicit trapezoid (midpoint lab, M2)"},
      rk4};
  info.sweep = true;
  wb::use_implicit(info);
  return wb::run_particle_lab(argc, argv, info);
}
