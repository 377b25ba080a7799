// The euler lab executable: scenes stepped with the student's two Euler steps.
#include "explicit_euler.h"
#include "forces_world.h"
#include "symplectic_euler.h"
#include "wb/run.h"

// Every lab's main has this shape: the lab's declaration (summary, integrators) handed to
// the run contract (docs/contributor.md, "Repeated code").
int main(int argc, char** argv) {
  wb::LabInfo info;
  info.lab = WB_LAB;
  info.side = WB_SIDE;
  info.summary = "Euler lab: explicit and semi-implicit Euler steps on particle scenes.";
  info.integrators = {
      {"explicit-euler", explicit_euler_step, 1, 1,
       "explicit Euler (TODO E1): positions with the old velocities"},
      {"symplectic-euler", symplectic_euler_step, 1, 1,
       "semi-implicit Euler (TODO E2): velocities first, positions with the new ones"}};
  info.sweep = true;
  wb::use_forces(info);
  return wb::run_particle_lab(argc, argv, info);
}
