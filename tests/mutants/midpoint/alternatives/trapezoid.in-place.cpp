#include "trapezoid.h"

// A correct variant: x and v are moved to X_a in place, the start is kept in
// xs, vs, and the average is formed from X_a and X_b = start + h f(X_a).
void trapezoid_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                    wb::Scratch& s) {
  s.xs = x;
  s.vs = v;
  dyn.acceleration(x, v, s.a2);
  x += h * v;  // X_a, in place
  v += h * s.a2;
  dyn.acceleration(x, v, s.a3);
  s.x1 = s.xs + h * v;  // X_b
  s.v1 = s.vs + h * s.a3;
  x = 0.5 * (x + s.x1);
  v = 0.5 * (v + s.v1);
}
