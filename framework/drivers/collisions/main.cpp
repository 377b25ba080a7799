// The collisions lab executable: particle scenes with the forces lab's forces,
// stepped with the provided semi-implicit Euler, and after every step the
// collision phase built from your C1..C4 (framework/drivers/collisions/contact_world.h).
#include "contact_world.h"
#include "wb/run.h"

namespace {

// Provided: v += h a(x, v); x += h v (the new velocity).
void semi_implicit_euler(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  dyn.acceleration(x, v, s.a0);
  v += h * s.a0;
  x += h * v;
}

}  // namespace

int main(int argc, char** argv) {
  wb::LabInfo info;
  info.lab = WB_LAB;
  info.side = WB_SIDE;
  info.summary =
      "Collisions lab: particles against planes and each other (impulses, a grid broad phase, "
      "friction and resting contact), stepped with semi-implicit Euler.";
  info.integrators = {{"symplectic-euler", semi_implicit_euler, 1, 1,
                       "semi-implicit Euler, provided: velocities first, then positions"}};
  wb::use_collisions(info);
  return wb::run_particle_lab(argc, argv, info);
}
