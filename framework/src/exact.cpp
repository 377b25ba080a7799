// Closed-form oscillator and Kepler motions for sweep mode's errors.
#include "wb/exact.h"

#include <cmath>

namespace wb {

void oscillator_exact(const Vec2& c, double w, const Vec2& x0, const Vec2& v0, double t, Vec2& x,
                      Vec2& v) {
  const double cs = std::cos(w * t), sn = std::sin(w * t);
  x = c + (x0 - c) * cs + v0 * (sn / w);
  v = -(x0 - c) * (w * sn) + v0 * cs;
}

double kepler_eccentric_anomaly(double M, double e) {
  // Reduce M to [-pi, pi]: E - M is 2 pi periodic in M.
  const double two_pi = 2.0 * M_PI;
  const double k = std::round(M / two_pi);
  const double m = M - k * two_pi;
  // F(E) = E - e sin E - m is increasing (F' = 1 - e cos E >= 1 - e > 0) and
  // |E - m| = e |sin E| <= e, so the root lies in [m - e, m + e].
  double lo = m - e, hi = m + e;
  double E = e < 0.8 ? m : (m >= 0 ? M_PI : -M_PI);  // a start that converges fast for high e
  E = std::min(std::max(E, lo), hi);
  for (int it = 0; it < 100; ++it) {
    const double F = E - e * std::sin(E) - m;
    if (F > 0)
      hi = E;
    else
      lo = E;
    double next = E - F / (1.0 - e * std::cos(E));          // Newton
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // left the bracket: bisect
    const bool done = std::abs(next - E) <= 4e-16 * (1.0 + std::abs(E));
    E = next;
    if (done || hi - lo <= 4e-16 * (1.0 + std::abs(E))) break;
  }
  return E + k * two_pi;
}

void kepler_exact(const Vec2& c, double GM, const Vec2& x0, const Vec2& v0, double t, Vec2& x,
                  Vec2& v) {
  const Vec2 r0 = x0 - c;  // position relative to the attractor
  const double r0n = r0.norm();
  const double eps = 0.5 * v0.squaredNorm() - GM / r0n;  // specific orbital energy (< 0)
  const double a = -GM / (2.0 * eps);                    // semi-major axis
  const double n = std::sqrt(GM / (a * a * a));          // mean motion (rad/s)
  // e cos E0 and e sin E0 from r = a (1 - e cos E) and r.v = sqrt(GM a) e sin E.
  const double ecos0 = 1.0 - r0n / a;
  const double esin0 = r0.dot(v0) / std::sqrt(GM * a);
  const double e = std::hypot(ecos0, esin0);
  const double E0 = std::atan2(esin0, ecos0);  // 0 for a circle: any start phase works
  // Whole periods change nothing: keep t in [0, P) so that g stays accurate.
  const double period = 2.0 * M_PI / n;
  const double tr = t - std::floor(t / period) * period;
  const double E = kepler_eccentric_anomaly(E0 - esin0 + n * tr, e);
  const double dE = E - E0;
  // Lagrange's coefficients: x = c + f r0 + g v0, v = fdot r0 + gdot v0.
  const double one_minus_cos = 1.0 - std::cos(dE);
  const double r = a * (1.0 - ecos0 * std::cos(dE) + esin0 * std::sin(dE));  // a (1 - e cos E)
  const double f = 1.0 - (a / r0n) * one_minus_cos;
  const double g = tr - (dE - std::sin(dE)) / n;
  const double fdot = -std::sqrt(GM * a) * std::sin(dE) / (r * r0n);
  const double gdot = 1.0 - (a / r) * one_minus_cos;
  x = c + f * r0 + g * v0;
  v = fdot * r0 + gdot * v0;
}

}  // namespace wb
