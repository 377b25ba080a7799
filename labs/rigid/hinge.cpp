#include "hinge.h"

#include <Eigen/Dense>

// TODO(R7) the point joint's impulse with drift correction (see hinge.h).
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

// TODO(R7) the revolute hinge: 3 point rows and 2 angular rows together (see hinge.h).
// Plan: 1. r = R r_body, u = R axis_body, (b1, b2) = tangent_basis(axis), B = [b1 b2];
//       2. the 5x5 K block by block (Eigen::Matrix<double, 5, 5>, .block / .topLeftCorner),
//          and rhs: the point's velocity and the two angular rows, with their drifts;
//       3. lambda = K.ldlt().solve(rhs); P = its first 3, M = B * its last 2;
//       4. v += P/m; omega += I^-1 (r x P + M); return {P, M}.
RevoluteImpulse apply_revolute(rigid::Body& b, const rigid::Vec3& r_body,
                               const rigid::Vec3& anchor, const rigid::Vec3& axis_body,
                               const rigid::Vec3& axis, double h, double beta) {
  // ---- Replace with your code ----
  (void)b, (void)r_body, (void)anchor, (void)axis_body, (void)axis, (void)h, (void)beta;
  return {};
  // ---- end ----
}
