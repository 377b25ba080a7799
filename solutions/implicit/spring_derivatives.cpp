#include "spring_derivatives.h"

#include <algorithm>
#include <cmath>

// TODO(I2) the spring's force and derivatives (see spring_derivatives.h).
void spring_derivatives(const wb::Vec2& xi, const wb::Vec2& xj, const wb::Vec2& vi,
                        const wb::Vec2& vj, double k, double rest, double kd, bool definite,
                        wb::Vec2& f, wb::Mat2& K, wb::Mat2& D) {
  const wb::Vec2 d = xi - xj;
  const double L = d.norm();
  // Both ends at one point: no direction.
  if (L == 0.0) {
    f.setZero();
    K = -k * wb::Mat2::Identity();
    D.setZero();
    return;
  }
  const wb::Vec2 u = d / L;
  const wb::Mat2 P = u * u.transpose();  // projection on the spring
  // Force: spring and damper along u.
  f = -(k * (L - rest) + kd * (vi - vj).dot(u)) * u;
  // Stiffness: along the spring k, across it k (1 - rest/L) (clamped if asked).
  double across = 1.0 - rest / L;
  if (definite) across = std::max(0.0, across);
  K = -k * (P + across * (wb::Mat2::Identity() - P));
  // Damping acts along the spring only.
  D = -kd * P;
}
