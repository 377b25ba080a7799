#include "collide_particles.h"

#include <cmath>

// Correct, written with the reduced mass mu = m1 m2 / (m1 + m2) and the mass
// fractions m2 / (m1 + m2), m1 / (m1 + m2) for the separation.
double collide_particles(double m1, double r1, double m2, double r2, double restitution,
                         wb::Vec2& x1, wb::Vec2& v1, wb::Vec2& x2, wb::Vec2& v2) {
  const double dist = (x1 - x2).norm();
  if (dist > r1 + r2) return 0.0;
  wb::Vec2 n(0.0, 1.0);
  if (dist != 0) n = (x1 - x2) / dist;
  const double overlap = r1 + r2 - dist;
  const double M = m1 + m2, mu = m1 * m2 / M;
  const double approach = (v2 - v1).dot(n);  // > 0 when approaching
  double J = 0.0;
  if (approach > 0) {
    J = (1 + restitution) * mu * approach;
    v1 = v1 + (J / m1) * n;
    v2 = v2 - (J / m2) * n;
  }
  x1 = x1 + overlap * (m2 / M) * n;
  x2 = x2 - overlap * (m1 / M) * n;
  return J;
}
