#include "curl_noise.h"

#include <algorithm>
#include <limits>

namespace {

// The smooth step of the paper: odd, ramp(0) = 0, ramp(+-1) = +-1, and its
// first and second derivatives vanish at +-1 (psi_c joins psi smoothly).
double ramp(double s) {
  if (s >= 1) return 1;
  if (s <= -1) return -1;
  const double s2 = s * s;
  return s * (15.0 / 8 - s2 * (10.0 / 8 - s2 * (3.0 / 8)));
}

}  // namespace

// TODO(F9) curl noise: psi ramped at the obstacles, its curl by central differences, and the
// drag b (u(x_i) - v_i) towards it.
double curl_noise_potential(const wb::Vec2& x, const CurlNoiseParams& p) {
  if (p.obstacles.empty()) return p.psi(x);
  double d = std::numeric_limits<double>::infinity();  // distance to the nearest edge
  for (const Disc& o : p.obstacles) d = std::min(d, (x - o.center).norm() - o.radius);
  return ramp(d / p.ramp) * p.psi(x);
}

wb::Vec2 curl_noise_flow(const wb::Vec2& x, const CurlNoiseParams& p) {
  const wb::Vec2 ex(p.h, 0), ey(0, p.h);
  const double dpsi_dx =
      (curl_noise_potential(x + ex, p) - curl_noise_potential(x - ex, p)) / (2 * p.h);
  const double dpsi_dy =
      (curl_noise_potential(x + ey, p) - curl_noise_potential(x - ey, p)) / (2 * p.h);
  return wb::Vec2(dpsi_dy, -dpsi_dx);
}

void add_curl_noise(const wb::Mat2X& x, const wb::Mat2X& v, const CurlNoiseParams& p,
                    wb::Mat2X& f) {
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    f.col(i) += p.b * (curl_noise_flow(x.col(i), p) - v.col(i));
  }
}
