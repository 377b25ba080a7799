#include "plane_contact.h"

#include <algorithm>
#include <cmath>

// Alternative: the angular part of the effective mass written as
// (r x u) . I^-1 (r x u), equal to u . ((I^-1 (r x u)) x r) (scalar triple product),
// with I^-1 built from the body's axes; the push-out from the lowest point.
namespace {

rigid::Mat3 inverse_inertia(const rigid::Body& b) {
  const rigid::Mat3 R = b.q.toRotationMatrix();
  rigid::Mat3 I_inv = rigid::Mat3::Zero();
  for (int k = 0; k < 3; ++k) I_inv += R.col(k) * R.col(k).transpose() / b.I_body(k, k);
  return I_inv;
}

}  // namespace

double contact_impulse(rigid::Body& b, const rigid::Vec3& p, const rigid::Vec3& n, double e,
                       double mu) {
  const rigid::Vec3 r = p - b.x;
  const double vn = n.dot(b.v + b.omega.cross(r));
  if (!(vn < 0.0)) return 0.0;
  const rigid::Mat3 I_inv = inverse_inertia(b);
  const rigid::Vec3 rn = r.cross(n);
  const double jn = -(1.0 + e) * vn / (1.0 / b.m + rn.dot(I_inv * rn));
  b.v += jn / b.m * n;
  b.omega += jn * (I_inv * rn);
  const rigid::Vec3 vp = b.v + b.omega.cross(r);
  const rigid::Vec3 vt = vp - n.dot(vp) * n;
  if (vt.squaredNorm() == 0.0) return jn;
  const rigid::Vec3 t = vt.normalized();
  const rigid::Vec3 rt = r.cross(t);
  const double stick = vt.norm() / (1.0 / b.m + rt.dot(I_inv * rt));
  const double jt = stick < mu * jn ? stick : mu * jn;
  b.v -= jt / b.m * t;
  b.omega -= jt * (I_inv * rt);
  return jn;
}

double resolve_plane_contact(rigid::Body& b, const std::vector<rigid::Vec3>& points,
                             const rigid::Vec3& point, const rigid::Vec3& n, double e,
                             double mu) {
  double total = 0.0;
  int pass = 0;
  bool again = true;
  while (again && pass < kContactPasses) {
    again = false;
    for (const rigid::Vec3& p : points) {
      if (n.dot(p - point) >= kContactSlop) continue;
      const double j = contact_impulse(b, p, n, e, mu);
      total += j;
      again = again || j > 0.0;
    }
    ++pass;
  }
  double lowest = 0.0;  // the lowest height over the plane, if below it
  for (const rigid::Vec3& p : points) lowest = std::min(lowest, n.dot(p - point));
  b.x -= lowest * n;
  return total;
}
