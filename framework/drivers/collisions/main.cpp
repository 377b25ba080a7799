// The collisions lab executable: particle scenes with the forces lab's forces,
// stepped with the provided semi-implicit Euler, and after every step the
// collision phase built from your C1..C4 (framework/drivers/collisions/contact_world.h).
#include "contact_world.h"
#include "wb/run.h"
#include "wb/semi_implicit.h"

// Every lab's main has this shape: the lab's declaration (summary, integrators) handed to
// the run contract (docs/contributor.md, "Repeated code").
int main(int argc, char** argv) {
  wb::LabInfo info;
  info.lab = WB_LAB;
  info.side = WB_SIDE;
  info.summary =
      "Collisions lab: particles against planes and each other (impulses, a grid broad phase, "
      "friction and resting contact), stepped with semi-implicit Euler.";
  info.integrators = {wb::semi_implicit_euler_integrator()};
  wb::use_collisions(info);
  return wb::run_particle_lab(argc, argv, info);
}
