#include "trapezoid.h"

// TODO(M2) trapezoid method: advance x and v by one step of size h (see trapezoid.h).
// Plan: 1. evaluate the accelerations at the start, (x, v), into s.a0;
//       2. build X_a in s.x1, s.v1: a full Euler step of size h;
//       3. evaluate the accelerations at X_a into s.a1;
//       4. X_b is a full step from the START (x, v) with the slope at X_a
//          (velocity s.v1, acceleration s.a1);
//       5. the new state is the average of X_a and X_b.
//       Exactly two calls to dyn.acceleration. Mind step 5: x and v still
//       hold the start of the step until you overwrite them.
void trapezoid_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                    wb::Scratch& s) {
  // ---- Replace with your code ----
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  // ---- end ----
}
