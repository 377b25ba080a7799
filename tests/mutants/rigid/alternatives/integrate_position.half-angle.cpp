#include "integrate_position.h"

#include <cmath>

// Alternative: the turn as a quaternion written by hand from the half angle,
// (cos(a/2), sin(a/2) u), with u = omega / |omega|.
void integrate_position(rigid::Body& b, double h) {
  b.x = b.x + b.v * h;
  const double angle = b.omega.norm() * h;
  if (angle == 0.0) return;
  const rigid::Vec3 s = std::sin(0.5 * angle) * b.omega.normalized();
  const Eigen::Quaterniond dq(std::cos(0.5 * angle), s.x(), s.y(), s.z());
  b.q = (dq * b.q).normalized();
}
