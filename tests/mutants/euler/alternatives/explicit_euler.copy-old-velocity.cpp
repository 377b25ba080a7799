#include "explicit_euler.h"

// Correct: keeps a copy of the old velocities in scratch, then updates v first.
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  dyn.acceleration(x, v, s.a0);
  s.v1 = v;           // v_n
  v = v + h * s.a0;   // v_{n+1}
  x = x + h * s.v1;   // x_{n+1} with v_n
}
