#include "trapezoid.h"

// A correct variant: X' = X + h/2 (f(X) + f(X_a)), the average of the two
// slopes, with no X_b written out.
void trapezoid_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                    wb::Scratch& s) {
  dyn.acceleration(x, v, s.a0);
  s.x1 = x + h * v;  // X_a
  s.v1 = v + h * s.a0;
  dyn.acceleration(s.x1, s.v1, s.a1);
  x += (0.5 * h) * (v + s.v1);
  v += (0.5 * h) * (s.a0 + s.a1);
}
