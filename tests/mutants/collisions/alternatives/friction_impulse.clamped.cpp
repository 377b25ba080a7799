#include "friction_impulse.h"

#include <algorithm>

// Correct, one formula: the tangential impulse is min(m |v_t|, mu jn) against v_t.
double friction_impulse(const wb::Vec2& n, double jn, double mu, double m, wb::Vec2& v) {
  const wb::Vec2 vt = v - v.dot(n) * n;
  const double speed = vt.norm();
  if (speed == 0) return 0.0;
  const double jt = std::min(m * speed, mu * jn);
  v -= (jt / m) * (vt / speed);
  return jt;
}
