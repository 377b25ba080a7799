#include "hinge.h"

#include <Eigen/Dense>

// Alternative: K built column by column from its definition (the pin's velocity
// change per unit impulse along each axis), and solved with a full-pivot LU.
rigid::Vec3 apply_hinge(rigid::Body& b, const rigid::Vec3& r_body, const rigid::Vec3& anchor,
                        double h, double beta) {
  const rigid::Mat3 R = b.q.toRotationMatrix();
  const rigid::Vec3 r = R * r_body;
  const rigid::Mat3 I_inv = R * b.I_body.inverse() * R.transpose();
  rigid::Mat3 K;
  for (int k = 0; k < 3; ++k) {
    const rigid::Vec3 e = rigid::Vec3::Unit(k);
    K.col(k) = e / b.m + (I_inv * r.cross(e)).cross(r);
  }
  const rigid::Vec3 target = -(beta / h) * (b.x + r - anchor);  // wanted pin velocity
  const rigid::Vec3 P = K.fullPivLu().solve(target - (b.v + b.omega.cross(r)));
  b.v += P / b.m;
  b.omega += I_inv * r.cross(P);
  return P;
}
