#include "trapezoid.h"

// A correct variant: (X_a + X_b)/2 expanded by hand,
//   x' = x + h/2 v + h/2 v_a,   v' = v + h/2 a_0 + h/2 a_a.
void trapezoid_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                    wb::Scratch& s) {
  const double half = 0.5 * h;
  dyn.acceleration(x, v, s.a0);
  s.v1 = v + h * s.a0;      // v_a
  s.x1 = x + h * v;         // x_a
  dyn.acceleration(s.x1, s.v1, s.a1);
  x += half * v;
  x += half * s.v1;
  v += half * s.a0;
  v += half * s.a1;
}
