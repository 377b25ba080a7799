#include "collide_particles.h"

#include <cmath>

double collide_particles(double m1, double r1, double m2, double r2, double restitution,
                         wb::Vec2& x1, wb::Vec2& v1, wb::Vec2& x2, wb::Vec2& v2) {
  const wb::Vec2 d = x1 - x2;
  const double dist = d.norm();
  const double s = r1 + r2 - dist;  // overlap
  if (s < 0) return 0.0;
  const wb::Vec2 n = dist > 0 ? wb::Vec2(d / dist) : wb::Vec2(0.0, 1.0);
  const double w1 = 1 / m1, w2 = 1 / m2;  // inverse masses
  // Impulse, only when approaching.
  const double vn = (v1 - v2).dot(n);
  double J = 0.0;
  if (vn < 0) {
    J = -(1 + restitution) * vn / (w1 + w2);
    v1 += (J * w1) * n;
    v2 -= (J * w2) * n;
  }
  // Separate without moving the centre of mass.
  x1 += (s * w1 / (w1 + w2)) * n;
  x2 -= (s * w2 / (w1 + w2)) * n;
  return J;
}
