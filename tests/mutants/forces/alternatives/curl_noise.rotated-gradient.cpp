// A correct F9 written differently: the gradient of psi_c by a loop over the
// two axes, then rotated by -90 degrees; the ramp in expanded form; the
// nearest edge found by comparing squared distances to the centres first.
#include <cmath>

#include "curl_noise.h"

double curl_noise_potential(const wb::Vec2& x, const CurlNoiseParams& p) {
  double d = 0;
  bool first = true;
  for (const Disc& o : p.obstacles) {
    const double e = std::sqrt((x - o.center).squaredNorm()) - o.radius;
    if (first || e < d) d = e;
    first = false;
  }
  if (first) return p.psi(x);
  double s = d / p.ramp;
  double r;
  if (s > 1) {
    r = 1;
  } else if (s < -1) {
    r = -1;
  } else {
    r = (15 * s - 10 * s * s * s + 3 * std::pow(s, 5)) / 8;
  }
  return r * p.psi(x);
}

wb::Vec2 curl_noise_flow(const wb::Vec2& x, const CurlNoiseParams& p) {
  wb::Vec2 grad;
  for (int k = 0; k < 2; ++k) {
    wb::Vec2 step = wb::Vec2::Zero();
    step[k] = p.h;
    grad[k] = 0.5 * (curl_noise_potential(x + step, p) - curl_noise_potential(x - step, p)) / p.h;
  }
  return -wb::perp(grad);  // (g_y, -g_x)
}

void add_curl_noise(const wb::Mat2X& x, const wb::Mat2X& v, const CurlNoiseParams& p,
                    wb::Mat2X& f) {
  for (Eigen::Index i = x.cols() - 1; i >= 0; --i) {
    const wb::Vec2 u = curl_noise_flow(x.col(i), p);
    f.col(i) += p.b * u - p.b * v.col(i);
  }
}
