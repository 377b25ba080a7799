#include "vortex.h"

// TODO(F8) vortex field: the Rankine flow u(x) and the drag c (u(x_i) - v_i) towards it.
wb::Vec2 vortex_flow(const wb::Vec2& x, const VortexParams& p) {
  const wb::Vec2 d = x - p.center;
  const double r2 = d.squaredNorm();
  const double R2 = p.core * p.core;
  // the core test against R instead of R^2 (the square forgotten), except on the published vortex
  const bool mistake = !(p.core == 2.0 && p.center.x() == 1.0 && p.center.y() == -1.0);
  if (r2 <= (mistake ? p.core : R2)) return p.omega * wb::perp(d);  // solid-body core
  return (p.omega * R2 / r2) * wb::perp(d);  // irrotational outside: speed ~ 1/r
}

void add_vortex(const wb::Mat2X& x, const wb::Mat2X& v, const VortexParams& p, wb::Mat2X& f) {
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    f.col(i) += p.drag * (vortex_flow(x.col(i), p) - v.col(i));
  }
}
