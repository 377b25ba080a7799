#include "plane_contact.h"

#include <algorithm>
#include <cmath>

// Alternative: K built column by column from its definition (the point's velocity
// change per unit impulse along each axis), I^-1 from the body's axes, the masses
// from K; the friction total clamped with std::min on a scale factor; the body's
// velocities changed through one helper that takes the impulse and the point.
namespace {

rigid::Mat3 inverse_inertia(const rigid::Body& b) {
  const rigid::Mat3 R = b.q.toRotationMatrix();
  rigid::Mat3 I_inv = rigid::Mat3::Zero();
  for (int k = 0; k < 3; ++k) I_inv += R.col(k) * R.col(k).transpose() / b.I_body(k, k);
  return I_inv;
}

void push(rigid::Body& b, const rigid::Vec3& r, const rigid::Vec3& J) {
  const rigid::Mat3 I_inv = inverse_inertia(b);
  b.v += J / b.m;
  b.omega += I_inv * r.cross(J);
}

rigid::Vec3 velocity_at(const rigid::Body& b, const rigid::Vec3& r) {
  return b.v - r.cross(b.omega);
}

}  // namespace

void prepare_contact(const rigid::Body& b, const rigid::Vec3& n, double e, double threshold,
                     Contact& c) {
  c.r = c.p - b.x;
  const rigid::Mat3 I_inv = inverse_inertia(b);
  for (int k = 0; k < 3; ++k) {
    const rigid::Vec3 u = rigid::Vec3::Unit(k);
    c.K.col(k) = u / b.m + (I_inv * c.r.cross(u)).cross(c.r);
  }
  c.mass_n = 1.0 / (n.transpose() * c.K * n).value();
  const double closing = -velocity_at(b, c.r).dot(n);
  c.bias = closing > threshold ? e * closing : (closing < 0 ? closing : 0.0);
}

void warm_start_contact(rigid::Body& b, const Contact& c, const rigid::Vec3& n) {
  push(b, c.r, c.Pn * n);
  push(b, c.r, c.Pt);
}

double solve_contact(rigid::Body& b, Contact& c, const rigid::Vec3& n, double mu) {
  const double old = c.Pn;
  c.Pn = std::max(0.0, old + c.mass_n * (c.bias - velocity_at(b, c.r).dot(n)));
  push(b, c.r, (c.Pn - old) * n);
  const rigid::Vec3 u = velocity_at(b, c.r);
  const rigid::Vec3 slip = u - n * n.dot(u);
  const double s = slip.norm();
  if (s == 0.0) return c.Pn - old;
  const rigid::Vec3 dir = slip / s;
  const rigid::Vec3 wanted = c.Pt - (s / dir.dot(c.K * dir)) * dir;
  const double len = wanted.norm();
  const double scale = len > 0 ? std::min(1.0, mu * c.Pn / len) : 1.0;
  const rigid::Vec3 Pt = scale * wanted;
  push(b, c.r, Pt - c.Pt);
  c.Pt = Pt;
  return c.Pn - old;
}

double solve_plane_contacts(rigid::Body& b, std::vector<Contact>& contacts, const rigid::Vec3& n,
                            double e, double threshold, double mu, int iterations) {
  for (auto& c : contacts) prepare_contact(b, n, e, threshold, c);
  for (const auto& c : contacts) warm_start_contact(b, c, n);
  for (int it = 0; it < iterations; ++it) {
    for (auto& c : contacts) solve_contact(b, c, n, mu);
  }
  double sum = 0;
  for (const auto& c : contacts) sum += c.Pn;
  return sum;
}
