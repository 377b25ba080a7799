#include "world_inertia.h"

// TODO(R2) world-frame inertia, its inverse, and the parallel axis theorem (see world_inertia.h).
rigid::Mat3 world_inertia(const rigid::Mat3& R, const rigid::Mat3& I_body) {
  return R * I_body * R.transpose();
}

rigid::Mat3 world_inverse_inertia(const rigid::Mat3& R, const rigid::Mat3& I_body) {
  const rigid::Vec3 inv = I_body.diagonal().cwiseInverse();  // I_body is diagonal
  return R * inv.asDiagonal() * R.transpose();
}

rigid::Mat3 parallel_axis(const rigid::Mat3& I, double m, const rigid::Vec3& d) {
  return I + m * (d.squaredNorm() * rigid::Mat3::Identity() - d * d.transpose());
}
