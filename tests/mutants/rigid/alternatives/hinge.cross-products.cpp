#include "hinge.h"

#include <cmath>

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

// Alternative: the revolute hinge as J M^-1 J^T with the 5x6 Jacobian written out,
// its own basis across the axis (not tangent_basis: any pair of perpendicular unit
// vectors gives the same motion), solved with a full-pivot LU.
RevoluteImpulse apply_revolute(rigid::Body& b, const rigid::Vec3& r_body,
                               const rigid::Vec3& anchor, const rigid::Vec3& axis_body,
                               const rigid::Vec3& axis, double h, double beta) {
  const rigid::Mat3 R = b.q.toRotationMatrix();
  const rigid::Vec3 r = R * r_body;
  const rigid::Vec3 u = R * axis_body;
  const rigid::Vec3 any = std::abs(axis.z()) < 0.9 ? rigid::Vec3::UnitZ() : rigid::Vec3::UnitX();
  const rigid::Vec3 c1 = axis.cross(any).normalized(), c2 = c1.cross(axis);
  Eigen::Matrix<double, 5, 6> J = Eigen::Matrix<double, 5, 6>::Zero();
  J.block<3, 3>(0, 0) = rigid::Mat3::Identity();
  J.block<3, 3>(0, 3) = -rigid::skew(r);
  J.block<1, 3>(3, 3) = c1.transpose();
  J.block<1, 3>(4, 3) = c2.transpose();
  Eigen::Matrix<double, 6, 6> W = Eigen::Matrix<double, 6, 6>::Zero();
  W.block<3, 3>(0, 0) = rigid::Mat3::Identity() / b.m;
  W.block<3, 3>(3, 3) = R * b.I_body.inverse() * R.transpose();
  Eigen::Matrix<double, 6, 1> V;
  V << b.v, b.omega;
  Eigen::Matrix<double, 5, 1> C;
  const rigid::Vec3 turn = axis.cross(u);
  C << b.x + r - anchor, c1.dot(turn), c2.dot(turn);
  const Eigen::Matrix<double, 5, 5> K = J * W * J.transpose();
  const Eigen::Matrix<double, 5, 1> lambda = K.fullPivLu().solve(-(J * V + beta / h * C));
  const Eigen::Matrix<double, 6, 1> dV = W * J.transpose() * lambda;
  b.v += dV.head<3>();
  b.omega += dV.tail<3>();
  RevoluteImpulse out;
  out.P = lambda.head<3>();
  out.M = lambda(3) * c1 + lambda(4) * c2;
  return out;
}
