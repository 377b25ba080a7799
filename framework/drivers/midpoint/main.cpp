// The midpoint lab executable: scenes stepped with the student's two
// second-order methods, and the provided RK4 as the reference.
#include "forces_world.h"
#include "midpoint.h"
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
      "Midpoint lab: the midpoint and trapezoid methods on particle scenes, with RK4 for "
      "reference.";
  wb::Integrator rk4 = wb::rk4_integrator();
  rk4.description = "classic Runge-Kutta, provided (not a task): the reference on the plots";
  info.integrators = {
      {"midpoint", midpoint_step, 2, 2,
       "midpoint method (TODO M1): a full step from X with the slope at X + h/2 f(X)"},
      {"trapezoid", trapezoid_step, 2, 2,
       "trapezoid method (TODO M2): the average of X + h f(X) and X + h f(X + h f(X))"},
      rk4};
  info.sweep = true;
  wb::use_forces(info);
  return wb::run_particle_lab(argc, argv, info);
}
