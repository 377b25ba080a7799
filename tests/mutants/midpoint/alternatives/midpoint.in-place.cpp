#include "midpoint.h"

// A correct variant: the start state is saved, x and v themselves are moved to
// the midpoint, and the full step is taken from the saved start.
void midpoint_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                   wb::Scratch& s) {
  s.xs = x;  // the start of the step
  s.vs = v;
  dyn.acceleration(x, v, s.a2);
  x += (0.5 * h) * v;     // x and v now hold the midpoint state
  v += (0.5 * h) * s.a2;
  dyn.acceleration(x, v, s.a3);
  x = s.xs + h * v;       // v is still the midpoint velocity here
  v = s.vs + h * s.a3;
}
