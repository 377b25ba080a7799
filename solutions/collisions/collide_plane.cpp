#include "collide_plane.h"

double collide_plane(const wb::Vec2& p, const wb::Vec2& n, double r, double m, double restitution,
                     double rest_speed, wb::Vec2& x, wb::Vec2& v) {
  const double d = (x - p).dot(n) - r;  // gap, <= 0 in contact
  if (d > 0) return 0.0;
  // Impulse, only when approaching.
  const double vn = v.dot(n);
  double j = 0.0;
  if (vn < 0) {
    const double e = -vn < rest_speed ? 0.0 : restitution;
    j = -(1 + e) * m * vn;
    v += (j / m) * n;
  }
  // Move out of the plane.
  x -= d * n;
  return j;
}
