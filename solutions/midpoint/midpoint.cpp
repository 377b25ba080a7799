#include "midpoint.h"

// TODO(M1) midpoint method: advance x and v by one step of size h (see midpoint.h).
void midpoint_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                   wb::Scratch& s) {
  // Evaluate the forces at the start of the step.
  dyn.acceleration(x, v, s.a0);
  // Half an Euler step to the midpoint state (x1, v1).
  s.x1 = x + (0.5 * h) * v;
  s.v1 = v + (0.5 * h) * s.a0;
  // Evaluate the forces at the midpoint.
  dyn.acceleration(s.x1, s.v1, s.a1);
  // A full step from the start with the midpoint slope (v1, a1).
  x += h * s.v1;
  v += h * s.a1;
}
