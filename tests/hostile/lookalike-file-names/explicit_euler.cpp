#include "explicit_euler.h"

// TODO(E1) explicit Euler: advance x and v by one step of size h (see explicit_euler.h).
// Plan: 1. evaluate the accelerations at the current state into s.a0 (once);
//       2. move the positions with the velocities you were given;
//       3. update the velocities with s.a0.
//       Mind the order of 2 and 3: which velocity moves the positions?
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  // ---- Replace with your code ----
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  // ---- end ----
}
