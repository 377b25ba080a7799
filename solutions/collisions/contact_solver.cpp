#include "contact_solver.h"

#include <algorithm>

namespace {

// u = v_a - v_b (v_b = 0 for a plane).
wb::Vec2 relative_velocity(const Contact& c, const wb::Mat2X& v) {
  return c.b >= 0 ? wb::Vec2(v.col(c.a) - v.col(c.b)) : wb::Vec2(v.col(c.a));
}

void apply(const wb::VecX& w, const Contact& c, const wb::Vec2& J, wb::Mat2X& v) {
  v.col(c.a) += w[c.a] * J;
  if (c.b >= 0) v.col(c.b) -= w[c.b] * J;
}

}  // namespace

// TODO(C5) effective mass and the restitution target (see contact_solver.h).
void prepare_contact(const wb::VecX& w, const wb::Mat2X& v, double e, double threshold,
                     Contact& c) {
  c.mass_n = 1.0 / (w[c.a] + (c.b >= 0 ? w[c.b] : 0.0));
  const double un = relative_velocity(c, v).dot(c.n);
  if (un > 0) {
    c.bias = -un;  // separating: turned back at most as fast as it leaves
  } else {
    c.bias = -un > threshold ? -e * un : 0.0;  // an impact bounces, a resting contact stops
  }
}

// TODO(C5) the totals of the last step, applied again (see contact_solver.h).
void warm_start_contact(const wb::VecX& w, const Contact& c, wb::Mat2X& v) {
  apply(w, c, c.Pn * c.n + c.Pt * wb::perp(c.n), v);
}

// TODO(C5) one iteration: accumulate, clamp the totals (see contact_solver.h).
double solve_contact(const wb::VecX& w, Contact& c, wb::Mat2X& v) {
  const wb::Vec2 t = wb::perp(c.n);
  // Normal: the total stays >= 0.
  const double lambda = c.mass_n * (c.bias - relative_velocity(c, v).dot(c.n));
  const double Pn = std::max(c.Pn + lambda, 0.0);
  const double dPn = Pn - c.Pn;
  c.Pn = Pn;
  apply(w, c, dPn * c.n, v);
  // Friction: the total stays within mu Pn.
  const double bound = c.mu * c.Pn;
  const double Pt = std::clamp(c.Pt - c.mass_n * relative_velocity(c, v).dot(t), -bound, bound);
  apply(w, c, (Pt - c.Pt) * t, v);
  c.Pt = Pt;
  return dPn;
}
