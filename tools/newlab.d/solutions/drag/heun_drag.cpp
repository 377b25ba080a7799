#include "heun_drag.h"

// TODO(D1) Heun's step: advance x and v by one step of size h (see heun_drag.h).
void heun_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v, wb::Scratch& s) {
  // Predict with explicit Euler.
  dyn.acceleration(x, v, s.a0);
  s.x1 = x + h * v;
  s.v1 = v + h * s.a0;
  // Correct with the average of the two slopes.
  dyn.acceleration(s.x1, s.v1, s.a1);
  x += 0.5 * h * (v + s.v1);
  v += 0.5 * h * (s.a0 + s.a1);
}
