#include "body_inertia.h"

// TODO(R1) the inertia tensors of a box, a sphere and a cylinder (see body_inertia.h).
// Plan: 1. write each diagonal entry from the formulas in the header;
//       2. return them as a diagonal 3x3 matrix (Vec3(...).asDiagonal()).
rigid::Mat3 box_inertia(double m, const rigid::Vec3& size) {
  // ---- Replace with your code ----
  (void)m, (void)size;
  return rigid::Mat3::Zero();
  // ---- end ----
}

rigid::Mat3 sphere_inertia(double m, double radius) {
  // ---- Replace with your code ----
  (void)m, (void)radius;
  return rigid::Mat3::Zero();
  // ---- end ----
}

rigid::Mat3 cylinder_inertia(double m, double radius, double length) {
  // ---- Replace with your code ----
  (void)m, (void)radius, (void)length;
  return rigid::Mat3::Zero();
  // ---- end ----
}
