#include "trapezoid.h"

// TODO(M2) trapezoid method: advance x and v by one step of size h (see trapezoid.h).
void trapezoid_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                    wb::Scratch& s) {
  // Evaluate the forces at the start of the step.
  dyn.acceleration(x, v, s.a0);
  // X_a: a full Euler step (x1, v1).
  s.x1 = x + h * v;
  s.v1 = v + h * s.a0;
  // Evaluate the forces at X_a.
  dyn.acceleration(s.x1, s.v1, s.a1);
  // X_b: a full step from the start with the slope at X_a (xs, vs).
  s.xs = x + h * s.v1;
  s.vs = v + h * s.a1;
  // The new state is the average of X_a and X_b.
  x = 0.5 * (s.x1 + s.xs);
  v = 0.5 * (s.v1 + s.vs);
}
