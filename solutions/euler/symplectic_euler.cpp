#include "symplectic_euler.h"

// TODO(E2) semi-implicit Euler: advance x and v by one step of size h (see symplectic_euler.h).
void symplectic_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                           wb::Scratch& s) {
  // Evaluate the forces at the start of the step.
  dyn.acceleration(x, v, s.a0);
  // Integrate velocities, then positions with the new velocities.
  v += h * s.a0;
  x += h * v;
}
