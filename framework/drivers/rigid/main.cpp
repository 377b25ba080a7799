// The rigid lab executable: 3D rigid bodies stepped with the student's functions.
#include "integrate_velocity.h"
#include "rigid_world.h"
#include "wb/run.h"  // WB_SIDE

// Every lab's main has this shape: the lab's declaration (summary, integrators) handed to
// the run contract (docs/contributor.md, "Repeated code").
int main(int argc, char** argv) {
  rigid::LabInfo info;
  info.lab = WB_LAB;
  info.side = WB_SIDE;
  info.summary =
      "Rigid lab: 3D rigid bodies (box, sphere, cylinder) with gravity, contact with planes "
      "and hinges, stepped with semi-implicit Euler.";
  info.integrators = {
      {"implicit-gyroscopic", integrate_velocity_implicit,
       "semi-implicit Euler, gyroscopic term by one Newton step in the body frame (TODO R5)"},
      {"explicit-gyroscopic", integrate_velocity_explicit,
       "semi-implicit Euler, gyroscopic term at the old omega: gains energy (TODO R5)"}};
  return rigid::run_rigid_lab(argc, argv, info);
}
