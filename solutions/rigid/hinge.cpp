#include "hinge.h"

#include <Eigen/Dense>

// TODO(R7) the hinge impulse with drift correction (see hinge.h).
rigid::Vec3 apply_hinge(rigid::Body& b, const rigid::Vec3& r_body, const rigid::Vec3& anchor,
                        double h, double beta) {
  const rigid::Mat3 R = b.q.toRotationMatrix();
  const rigid::Vec3 r = R * r_body;                // centre -> pinned point, world
  const rigid::Vec3 drift = b.x + r - anchor;      // C (m)
  const rigid::Vec3 v_p = b.v + b.omega.cross(r);  // velocity of the pinned point
  const rigid::Mat3 I_inv = R * b.I_body.diagonal().cwiseInverse().asDiagonal() * R.transpose();
  const rigid::Mat3 rx = rigid::skew(r);
  const rigid::Mat3 K = rigid::Mat3::Identity() / b.m - rx * I_inv * rx;
  const rigid::Vec3 P = K.ldlt().solve(-(v_p + beta / h * drift));
  b.v += P / b.m;
  b.omega += I_inv * r.cross(P);
  return P;
}
