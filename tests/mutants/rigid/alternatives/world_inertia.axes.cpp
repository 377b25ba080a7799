#include "world_inertia.h"

// Alternative: the tensors as sums over the body's principal axes a_k = R e_k,
//   I = sum_k I_k a_k a_k^T,   I^-1 = sum_k a_k a_k^T / I_k,
// and the parallel axis theorem entry by entry.
rigid::Mat3 world_inertia(const rigid::Mat3& R, const rigid::Mat3& I_body) {
  rigid::Mat3 I = rigid::Mat3::Zero();
  for (int k = 0; k < 3; ++k) I += I_body(k, k) * R.col(k) * R.col(k).transpose();
  return I;
}

rigid::Mat3 world_inverse_inertia(const rigid::Mat3& R, const rigid::Mat3& I_body) {
  rigid::Mat3 I_inv = rigid::Mat3::Zero();
  for (int k = 0; k < 3; ++k) I_inv += R.col(k) * R.col(k).transpose() / I_body(k, k);
  return I_inv;
}

rigid::Mat3 parallel_axis(const rigid::Mat3& I, double m, const rigid::Vec3& d) {
  rigid::Mat3 out = I;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out(i, j) += m * ((i == j ? d.dot(d) : 0.0) - d[i] * d[j]);
  }
  return out;
}
