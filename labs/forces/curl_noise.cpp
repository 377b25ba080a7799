#include "curl_noise.h"

// TODO(F9) curl noise: psi ramped at the obstacles, its curl by central differences, and the
// drag b (u(x_i) - v_i) towards it.
double curl_noise_potential(const wb::Vec2& x, const CurlNoiseParams& p) {
  // ---- Replace with your code ----
  (void)x, (void)p;
  return 0.0;
  // ---- end ----
}

wb::Vec2 curl_noise_flow(const wb::Vec2& x, const CurlNoiseParams& p) {
  // ---- Replace with your code ----
  (void)x, (void)p;
  return wb::Vec2::Zero();
  // ---- end ----
}

void add_curl_noise(const wb::Mat2X& x, const wb::Mat2X& v, const CurlNoiseParams& p,
                    wb::Mat2X& f) {
  // ---- Replace with your code ----
  (void)x, (void)v, (void)p, (void)f;
  // ---- end ----
}
