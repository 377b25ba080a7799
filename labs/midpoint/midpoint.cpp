#include "midpoint.h"

// TODO(M1) midpoint method: advance x and v by one step of size h (see midpoint.h).
// Plan: 1. evaluate the accelerations at the start, (x, v), into s.a0;
//       2. build the midpoint state in s.x1, s.v1: half an Euler step (h/2);
//       3. evaluate the accelerations at the midpoint into s.a1;
//       4. take the full step from the START: positions with the midpoint
//          velocities s.v1, velocities with the midpoint accelerations s.a1.
//       Exactly two calls to dyn.acceleration.
void midpoint_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                   wb::Scratch& s) {
  // ---- Replace with your code ----
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  // ---- end ----
}
