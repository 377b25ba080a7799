#include "plane_contact.h"

#include <algorithm>

#include <Eigen/Dense>

namespace {

rigid::Mat3 inverse_inertia(const rigid::Body& b) {
  const rigid::Mat3 R = b.q.toRotationMatrix();
  return R * b.I_body.diagonal().cwiseInverse().asDiagonal() * R.transpose();
}

// An impulse J at the point r from the centre.
void apply_impulse(rigid::Body& b, const rigid::Vec3& r, const rigid::Vec3& J) {
  b.v += J / b.m;
  b.omega += inverse_inertia(b) * r.cross(J);
}

rigid::Vec3 point_velocity(const rigid::Body& b, const rigid::Vec3& r) {
  return b.v + b.omega.cross(r);
}

}  // namespace

// TODO(R6) effective masses and the restitution target (see plane_contact.h).
void prepare_contact(const rigid::Body& b, const rigid::Vec3& n, double e, double threshold,
                     Contact& c) {
  c.r = c.p - b.x;
  const rigid::Mat3 rx = rigid::skew(c.r);
  c.K = rigid::Mat3::Identity() / b.m - rx * inverse_inertia(b) * rx;
  c.mass_n = 1.0 / n.dot(c.K * n);
  const double vn = point_velocity(b, c.r).dot(n);  // before any impulse of this step
  if (vn > 0) {
    c.bias = -vn;  // separating: turned back at most as fast as it leaves
  } else {
    c.bias = -vn > threshold ? -e * vn : 0.0;  // an impact bounces, a resting contact stops
  }
}

// TODO(R6) apply the totals kept from the previous step (see plane_contact.h).
void warm_start_contact(rigid::Body& b, const Contact& c, const rigid::Vec3& n) {
  apply_impulse(b, c.r, c.Pn * n + c.Pt);
}

// TODO(R6) one iteration on one contact: accumulate, clamp the totals (see plane_contact.h).
double solve_contact(rigid::Body& b, Contact& c, const rigid::Vec3& n, double mu) {
  // Normal: the total stays >= 0.
  const double lambda = c.mass_n * (c.bias - point_velocity(b, c.r).dot(n));
  const double Pn = std::max(c.Pn + lambda, 0.0);
  const double dPn = Pn - c.Pn;
  c.Pn = Pn;
  apply_impulse(b, c.r, dPn * n);
  // Friction: against the sliding, the total within the disc of radius mu Pn.
  const rigid::Vec3 u = point_velocity(b, c.r);
  const rigid::Vec3 ut = u - u.dot(n) * n;
  const double slip = ut.norm();
  if (slip > 0) {
    const rigid::Vec3 d = ut / slip;
    rigid::Vec3 Pt = c.Pt - slip / d.dot(c.K * d) * d;
    const double bound = mu * c.Pn;
    if (Pt.norm() > bound) Pt *= bound / Pt.norm();
    apply_impulse(b, c.r, Pt - c.Pt);
    c.Pt = Pt;
  }
  return dPn;
}

// TODO(R6) every contact of a body with a plane, together (see plane_contact.h).
double solve_plane_contacts(rigid::Body& b, std::vector<Contact>& contacts, const rigid::Vec3& n,
                            double e, double threshold, double mu, int iterations) {
  for (Contact& c : contacts) prepare_contact(b, n, e, threshold, c);
  for (const Contact& c : contacts) warm_start_contact(b, c, n);
  for (int it = 0; it < iterations; ++it) {
    for (Contact& c : contacts) solve_contact(b, c, n, mu);
  }
  double total = 0;
  for (const Contact& c : contacts) total += c.Pn;
  return total;
}
