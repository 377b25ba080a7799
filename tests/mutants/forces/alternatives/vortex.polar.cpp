// Correct alternative: the flow in polar form, speed(r) times the unit tangent,
// with the core test r < R (the two formulas agree at r = R).
#include "vortex.h"

wb::Vec2 vortex_flow(const wb::Vec2& x, const VortexParams& p) {
  const wb::Vec2 d = x - p.center;
  const double r = d.norm();
  if (r == 0) return wb::Vec2(0, 0);
  const wb::Vec2 tangent(-d.y() / r, d.x() / r);  // counter-clockwise unit tangent
  const double speed = r < p.core ? p.omega * r : p.omega * p.core * p.core / r;
  return speed * tangent;
}

void add_vortex(const wb::Mat2X& x, const wb::Mat2X& v, const VortexParams& p, wb::Mat2X& f) {
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const wb::Vec2 u = vortex_flow(x.col(i), p);
    f(0, i) += p.drag * u.x() - p.drag * v(0, i);
    f(1, i) += p.drag * u.y() - p.drag * v(1, i);
  }
}
