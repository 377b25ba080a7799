#include "plane_contact.h"

#include <algorithm>
#include <cmath>

namespace {

// The change of velocity at a point r from the centre, per unit impulse along u:
// 1/m + u . ((I^-1 (r x u)) x r).
double inverse_effective_mass(const rigid::Body& b, const rigid::Mat3& I_inv,
                              const rigid::Vec3& r, const rigid::Vec3& u) {
  return 1.0 / b.m + u.dot((I_inv * r.cross(u)).cross(r));
}

void apply_impulse(rigid::Body& b, const rigid::Mat3& I_inv, const rigid::Vec3& r,
                   const rigid::Vec3& J) {
  b.v += J / b.m;
  b.omega += I_inv * r.cross(J);
}

}  // namespace

// TODO(R6) contact impulse with restitution and Coulomb friction (see plane_contact.h).
double contact_impulse(rigid::Body& b, const rigid::Vec3& p, const rigid::Vec3& n, double e,
                       double mu) {
  const rigid::Vec3 r = p - b.x;
  const double vn = (b.v + b.omega.cross(r)).dot(n);
  if (vn >= 0.0) return 0.0;  // separating or resting: no impulse
  const rigid::Mat3 R = b.q.toRotationMatrix();
  const rigid::Mat3 I_inv = R * b.I_body.diagonal().cwiseInverse().asDiagonal() * R.transpose();
  // Normal impulse.
  const double jn = -(1.0 + e) * vn / inverse_effective_mass(b, I_inv, r, n);
  apply_impulse(b, I_inv, r, jn * n);
  // Friction, against the sliding that is left.
  const rigid::Vec3 v_rel = b.v + b.omega.cross(r);
  const rigid::Vec3 vt = v_rel - v_rel.dot(n) * n;
  const double speed = vt.norm();
  if (speed > 0.0) {
    const rigid::Vec3 t = vt / speed;
    const double jt = std::min(speed / inverse_effective_mass(b, I_inv, r, t), mu * jn);
    apply_impulse(b, I_inv, r, -jt * t);
  }
  return jn;
}

// TODO(R6) every point of a body against a plane (see plane_contact.h).
double resolve_plane_contact(rigid::Body& b, const std::vector<rigid::Vec3>& points,
                             const rigid::Vec3& point, const rigid::Vec3& n, double e,
                             double mu) {
  double total = 0.0;
  for (int pass = 0; pass < kContactPasses; ++pass) {
    double applied = 0.0;
    for (const rigid::Vec3& p : points) {
      if ((p - point).dot(n) < kContactSlop) applied += contact_impulse(b, p, n, e, mu);
    }
    total += applied;
    if (applied == 0.0) break;
  }
  // Push the body out of the plane by the deepest penetration.
  double depth = 0.0;
  for (const rigid::Vec3& p : points) depth = std::max(depth, (point - p).dot(n));
  b.x += depth * n;
  return total;
}
