#include "spring.h"

// TODO(F5) spring-damper: the force on end i (see spring.h for the formula).
wb::Vec2 spring_force(const wb::Vec2& xi, const wb::Vec2& xj, const wb::Vec2& vi,
                      const wb::Vec2& vj, double k, double rest, double kd) {
  const wb::Vec2 d = xi - xj;
  const double L = d.norm();
  if (L == 0.0) return wb::Vec2::Zero();  // no direction to push along
  const wb::Vec2 u = d / L;
  const double tension = k * (L - rest) + kd * (vi - vj).dot(u);  // > 0 pulls i towards j
  return -tension * u;
}
