#include "world_inertia.h"

// TODO(R2) world-frame inertia, its inverse, and the parallel axis theorem (see world_inertia.h).
// Plan: 1. world_inertia: R I_body R^T;
//       2. world_inverse_inertia: the same with the diagonal of 1 / I_body's entries;
//       3. parallel_axis: I + m (d.d E - d d^T).
rigid::Mat3 world_inertia(const rigid::Mat3& R, const rigid::Mat3& I_body) {
  // ---- Replace with your code ----
  (void)R, (void)I_body;
  return rigid::Mat3::Zero();
  // ---- end ----
}

rigid::Mat3 world_inverse_inertia(const rigid::Mat3& R, const rigid::Mat3& I_body) {
  // ---- Replace with your code ----
  (void)R, (void)I_body;
  return rigid::Mat3::Zero();
  // ---- end ----
}

rigid::Mat3 parallel_axis(const rigid::Mat3& I, double m, const rigid::Vec3& d) {
  // ---- Replace with your code ----
  (void)I, (void)m, (void)d;
  return rigid::Mat3::Zero();
  // ---- end ----
}
