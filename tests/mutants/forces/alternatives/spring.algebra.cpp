// Correct alternative: the same force with different algebra, never forming u:
//   f_i = -k (1 - rest / L) d - kd ((v_i - v_j) . d / L^2) d.
#include "spring.h"

#include <cmath>

wb::Vec2 spring_force(const wb::Vec2& xi, const wb::Vec2& xj, const wb::Vec2& vi,
                      const wb::Vec2& vj, double k, double rest, double kd) {
  const wb::Vec2 d = xi - xj;
  const double L2 = d.dot(d);
  if (!(L2 > 0)) return wb::Vec2(0, 0);
  const double L = std::sqrt(L2);
  return -k * (1.0 - rest / L) * d - kd * ((vi - vj).dot(d) / L2) * d;
}
