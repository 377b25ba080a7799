#include <algorithm>
#include <cmath>

#include "spring_derivatives.h"

// Alternative I2: K written as -k ((1 - r/L) I + (r/L) u u^T), entry by entry.
void spring_derivatives(const wb::Vec2& xi, const wb::Vec2& xj, const wb::Vec2& vi,
                        const wb::Vec2& vj, double k, double rest, double kd, bool definite,
                        wb::Vec2& f, wb::Mat2& K, wb::Mat2& D) {
  const double dx = xi.x() - xj.x(), dy = xi.y() - xj.y();
  const double L = std::sqrt(dx * dx + dy * dy);
  if (!(L > 0.0)) {
    f = wb::Vec2(0.0, 0.0);
    K << -k, 0.0, 0.0, -k;
    D << 0.0, 0.0, 0.0, 0.0;
    return;
  }
  const double ux = dx / L, uy = dy / L;
  const double s = k * (L - rest) + kd * ((vi.x() - vj.x()) * ux + (vi.y() - vj.y()) * uy);
  f = wb::Vec2(-s * ux, -s * uy);
  const double a = definite ? std::max(0.0, 1.0 - rest / L) : 1.0 - rest / L;  // across
  const double c = 1.0 - a;                                                    // = r/L unclamped
  K << -k * (a + c * ux * ux), -k * c * ux * uy, -k * c * ux * uy, -k * (a + c * uy * uy);
  D << -kd * ux * ux, -kd * ux * uy, -kd * ux * uy, -kd * uy * uy;
}
