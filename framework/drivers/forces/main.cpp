// The forces lab executable: scenes stepped with the provided semi-implicit Euler.
#include "forces_world.h"
#include "wb/run.h"
#include "wb/semi_implicit.h"

// Every lab's main has this shape: the lab's declaration (summary, integrators) handed to
// the run contract (docs/contributor.md, "Repeated code").
int main(int argc, char** argv) {
  wb::LabInfo info;
  info.lab = WB_LAB;
  info.side = WB_SIDE;
  info.summary =
      "Forces lab: particles under the forces you write, stepped with semi-implicit Euler.";
  info.integrators = {wb::semi_implicit_euler_integrator()};
  wb::use_forces(info);
  return wb::run_particle_lab(argc, argv, info);
}
