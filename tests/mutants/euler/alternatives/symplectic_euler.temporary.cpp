#include "symplectic_euler.h"

// Correct: the new velocities go to scratch first, then to both x and v.
void symplectic_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                           wb::Scratch& s) {
  dyn.acceleration(x, v, s.a0);
  s.v1.noalias() = v + h * s.a0;  // v_{n+1}
  x.noalias() += h * s.v1;        // x_{n+1} with v_{n+1}
  v = s.v1;
}
