#include "integrate_position.h"

// TODO(R4) move the centre with the new velocity and turn the body by |omega| h
// about omega (see integrate_position.h).
// Plan: 1. x += h v;
//       2. angle = |omega| h; if it is not zero, dq = Eigen::AngleAxisd(angle, axis);
//       3. q = dq * q, then q.normalize().
void integrate_position(rigid::Body& b, double h) {
  // ---- Replace with your code ----
  (void)b, (void)h;
  // ---- end ----
}
