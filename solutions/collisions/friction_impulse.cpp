#include "friction_impulse.h"

double friction_impulse(const wb::Vec2& n, double jn, double mu, double m, wb::Vec2& v) {
  const wb::Vec2 vt = v - v.dot(n) * n;  // tangential velocity
  const double speed = vt.norm();
  const double stop = m * speed;  // impulse that stops the sliding
  const double bound = mu * jn;   // Coulomb's cone
  if (stop <= bound) {
    v -= vt;  // static
    return stop;
  }
  v -= (bound / m) * (vt / speed);  // sliding
  return bound;
}
