#include "hinge.h"

#include <Eigen/Dense>

namespace {

rigid::Mat3 inverse_inertia(const rigid::Body& b) {
  const rigid::Mat3 R = b.q.toRotationMatrix();
  return R * b.I_body.diagonal().cwiseInverse().asDiagonal() * R.transpose();
}

}  // namespace

// TODO(R7) the point joint's impulse with drift correction (see hinge.h).
rigid::Vec3 apply_hinge(rigid::Body& b, const rigid::Vec3& r_body, const rigid::Vec3& anchor,
                        double h, double beta) {
  const rigid::Mat3 R = b.q.toRotationMatrix();
  const rigid::Vec3 r = R * r_body;                // centre -> pinned point, world
  const rigid::Vec3 drift = b.x + r - anchor;      // C (m)
  const rigid::Vec3 v_p = b.v + b.omega.cross(r);  // velocity of the pinned point
  const rigid::Mat3 I_inv = inverse_inertia(b);
  const rigid::Mat3 rx = rigid::skew(r);
  const rigid::Mat3 K = rigid::Mat3::Identity() / b.m - rx * I_inv * rx;
  const rigid::Vec3 P = K.ldlt().solve(-(v_p + beta / h * drift));
  b.v += P / b.m;
  b.omega += I_inv * r.cross(P);
  return P;
}

// TODO(R7) the revolute hinge: 3 point rows and 2 angular rows together (see hinge.h).
RevoluteImpulse apply_revolute(rigid::Body& b, const rigid::Vec3& r_body,
                               const rigid::Vec3& anchor, const rigid::Vec3& axis_body,
                               const rigid::Vec3& axis, double h, double beta) {
  const rigid::Mat3 R = b.q.toRotationMatrix();
  const rigid::Vec3 r = R * r_body;
  const rigid::Vec3 u = R * axis_body;  // the body's axis, world
  rigid::Vec3 b1, b2;
  rigid::tangent_basis(axis, b1, b2);
  Eigen::Matrix<double, 3, 2> B;
  B << b1, b2;
  const rigid::Mat3 I_inv = inverse_inertia(b);
  const rigid::Mat3 rx = rigid::skew(r);
  // The effective-mass matrix, block by block.
  Eigen::Matrix<double, 5, 5> K;
  K.topLeftCorner<3, 3>() = rigid::Mat3::Identity() / b.m - rx * I_inv * rx;
  K.topRightCorner<3, 2>() = -rx * I_inv * B;
  K.bottomLeftCorner<2, 3>() = B.transpose() * I_inv * rx;
  K.bottomRightCorner<2, 2>() = B.transpose() * I_inv * B;
  // The velocity errors with the drift correction.
  Eigen::Matrix<double, 5, 1> rhs;
  rhs.head<3>() = -(b.v + b.omega.cross(r) + beta / h * (b.x + r - anchor));
  rhs.tail<2>() = -(B.transpose() * b.omega + beta / h * B.transpose() * axis.cross(u));
  const Eigen::Matrix<double, 5, 1> lambda = K.ldlt().solve(rhs);
  RevoluteImpulse J;
  J.P = lambda.head<3>();
  J.M = B * lambda.tail<2>();
  b.v += J.P / b.m;
  b.omega += I_inv * (r.cross(J.P) + J.M);
  return J;
}
