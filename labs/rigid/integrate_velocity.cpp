#include "integrate_velocity.h"

#include <Eigen/Dense>

// TODO(R5) semi-implicit Euler for the velocities: explicit and implicit gyroscopic
// term (see integrate_velocity.h).
// Plan: 1. v += h f / m (both);
//       2. R from q; the world inertia I and its inverse (R2);
//       3. explicit: omega += h I^-1 (tau - omega x (I omega));
//       4. implicit: w = R^T omega; J; w' = w - J^-1 (h w x (I_body w));
//          omega = R w' + h I^-1 tau.
void integrate_velocity_explicit(rigid::Body& b, double h) {
  // ---- Replace with your code ----
  (void)b, (void)h;
  // ---- end ----
}

void integrate_velocity_implicit(rigid::Body& b, double h) {
  // ---- Replace with your code ----
  (void)b, (void)h;
  // ---- end ----
}
