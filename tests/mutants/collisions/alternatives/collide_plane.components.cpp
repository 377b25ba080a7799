#include "collide_plane.h"

// Correct, written with the normal and tangential parts of the velocity: the
// normal part is replaced by -e times itself, the tangential part is kept.
double collide_plane(const wb::Vec2& p, const wb::Vec2& n, double r, double m, double restitution,
                     double rest_speed, wb::Vec2& x, wb::Vec2& v) {
  const double depth = r - (x - p).dot(n);  // >= 0 in contact
  if (depth < 0) return 0.0;
  x = x + depth * n;
  const double vn = v.dot(n);
  if (vn >= 0) return 0.0;
  const wb::Vec2 vt = v - vn * n;
  const double e = (-vn >= rest_speed) ? restitution : 0.0;
  v = vt - e * vn * n;
  return m * (1 + e) * (-vn);
}
