#include <cmath>

#include "integrate_position.h"

// Alternative: dq = (cos(a/2), sinc(a/2) h omega / 2), a = |omega| h, with
// sinc(s) = sin(s) / s written as its Taylor series for small s: no branch on
// omega = 0 is needed, and a slow spin still turns the body.
void integrate_position(rigid::Body& b, double h) {
  b.x += h * b.v;
  const double half = 0.5 * h * b.omega.norm();  // a / 2 (rad)
  const double sinc = half < 1e-4 ? 1.0 - half * half / 6.0 : std::sin(half) / half;
  const rigid::Vec3 s = (0.5 * h * sinc) * b.omega;
  b.q = Eigen::Quaterniond(std::cos(half), s.x(), s.y(), s.z()) * b.q;
  b.q.normalize();
}
