#include "body_inertia.h"

// TODO(R1) the inertia tensors of a box, a sphere and a cylinder (see body_inertia.h).
rigid::Mat3 box_inertia(double m, const rigid::Vec3& size) {
  const rigid::Vec3 s2 = size.cwiseProduct(size);  // a^2, b^2, c^2
  return (m / 12.0 * rigid::Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y())).asDiagonal();
}

rigid::Mat3 sphere_inertia(double m, double radius) {
  return rigid::Mat3::Identity() * (0.4 * m * radius * radius);
}

rigid::Mat3 cylinder_inertia(double m, double radius, double length) {
  const double across = m / 12.0 * (3.0 * radius * radius + length * length);  // about x, y
  const double along = 0.5 * m * radius * radius;                              // about z
  return rigid::Vec3(across, across, along).asDiagonal();
}
