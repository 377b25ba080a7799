#include "contact_solver.h"

#include <algorithm>
#include <cmath>

// Alternative: the impulses applied component by component with the reduced mass
// m_a m_b / (m_a + m_b) written from the masses; the friction clamp with min/max;
// the plane handled by its own branch.
void prepare_contact(const wb::VecX& w, const wb::Mat2X& v, double e, double threshold,
                     Contact& c) {
  double un = v.col(c.a).dot(c.n);
  if (c.b < 0) {
    c.mass_n = 1.0 / w[c.a];
  } else {
    const double ma = 1.0 / w[c.a], mb = 1.0 / w[c.b];
    c.mass_n = ma * mb / (ma + mb);
    un -= v.col(c.b).dot(c.n);
  }
  // Closing faster than the threshold: bounce; closing slower: stop; leaving: -un.
  c.bias = (-un > threshold) ? e * -un : std::min(0.0, -un);
}

void warm_start_contact(const wb::VecX& w, const Contact& c, wb::Mat2X& v) {
  const wb::Vec2 t(-c.n.y(), c.n.x());
  for (int k = 0; k < 2; ++k) {
    const double J = c.Pn * c.n[k] + c.Pt * t[k];
    v(k, c.a) += w[c.a] * J;
    if (c.b >= 0) v(k, c.b) -= w[c.b] * J;
  }
}

double solve_contact(const wb::VecX& w, Contact& c, wb::Mat2X& v) {
  const wb::Vec2 t(-c.n.y(), c.n.x());
  auto rel = [&]() {
    wb::Vec2 u = v.col(c.a);
    if (c.b >= 0) u -= v.col(c.b);
    return u;
  };
  const double old = c.Pn;
  c.Pn = std::max(0.0, old + c.mass_n * (c.bias - rel().dot(c.n)));
  const double dn = c.Pn - old;
  v.col(c.a) += w[c.a] * dn * c.n;
  if (c.b >= 0) v.col(c.b) -= w[c.b] * dn * c.n;
  const double oldt = c.Pt;
  const double limit = c.mu * c.Pn;
  c.Pt = std::min(limit, std::max(-limit, oldt - c.mass_n * rel().dot(t)));
  const double dt = c.Pt - oldt;
  v.col(c.a) += w[c.a] * dt * t;
  if (c.b >= 0) v.col(c.b) -= w[c.b] * dt * t;
  return dn;
}
