#include "symplectic_euler.h"

// TODO(E2) semi-implicit Euler: advance x and v by one step of size h (see symplectic_euler.h).
// Plan: 1. evaluate the accelerations at the current state into s.a0 (once);
//       2. update the velocities with s.a0;
//       3. move the positions with the velocities you just computed.
void symplectic_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                           wb::Scratch& s) {
  // ---- Replace with your code ----
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  // ---- end ----
}
