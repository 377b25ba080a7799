#include "hinge.h"

#include <Eigen/Dense>

// TODO(R7) the hinge impulse with drift correction (see hinge.h).
// Plan: 1. r = R r_body, C = x + r - anchor, v_p = v + omega x r;
//       2. I^-1 in the world frame (R2); K = E/m - [r]x I^-1 [r]x;
//       3. P = K^-1 (-(v_p + beta/h C)); v += P/m; omega += I^-1 (r x P); return P.
rigid::Vec3 apply_hinge(rigid::Body& b, const rigid::Vec3& r_body, const rigid::Vec3& anchor,
                        double h, double beta) {
  // ---- Replace with your code ----
  (void)b, (void)r_body, (void)anchor, (void)h, (void)beta;
  return rigid::Vec3::Zero();
  // ---- end ----
}
