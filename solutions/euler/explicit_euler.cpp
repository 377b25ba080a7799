#include "explicit_euler.h"

// TODO(E1) explicit Euler: advance x and v by one step of size h (see explicit_euler.h).
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  // Evaluate the forces at the start of the step.
  dyn.acceleration(x, v, s.a0);
  // Integrate positions with the old velocities, then velocities.
  x += h * v;
  v += h * s.a0;
}
