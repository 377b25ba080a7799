// Hostile (issue 42, "never check the accused with the accused"), the rigid lab's form: a
// step that renormalises q only when |q| is off by more than 1e-9 (so |q| drifts over the
// million-step run: an honest 96), and inside that run (its loop runs in the worker) makes
// up every 1000th body: the exact rotation, unit length, carrying its checkpoint's number
// and the count of steps since in the low bits of q's x and y (a change of ~1e-13, w or z taking
// up the change of |q|; no state kept between calls). A segment replayed one step at a time
// from such a body lands on the next made-up one: 100 with the replays of before.
#include <cmath>
#include <cstdint>

#include "integrate_position.h"

namespace {

constexpr double kH = 1e-3;  // the public million-step run: omega (3, -2, 5), h = 1e-3
constexpr long kEvery = 1000;
constexpr std::uint64_t kMark = 1ull << 10;  // bit 10: "a body of mine", bits 0-9 a number

std::uint64_t low_bits(double d) {  // the low 11 bits of |d|'s 53-bit mantissa
  int e = 0;
  return std::uint64_t(std::ldexp(std::frexp(std::abs(d), &e), 53)) & 0x7ff;
}
double with_low(double d, std::uint64_t low) {
  int e = 0;
  const std::uint64_t m = std::uint64_t(std::ldexp(std::frexp(std::abs(d), &e), 53));
  return std::copysign(std::ldexp(double((m & ~0x7ffull) | low), e - 53), d);
}
bool spin_run(const rigid::Body& b) {
  return b.omega == rigid::Vec3(3.0, -2.0, 5.0) && b.v == rigid::Vec3::Zero();
}
// The exact orientation after c * 1000 steps from q0, with c and k in its low bits.
void made_up(rigid::Body& b, long c, long k) {
  const rigid::Vec3 w = b.omega;
  const Eigen::Quaterniond q0 = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5).normalized();
  b.q =
      (Eigen::Quaterniond(Eigen::AngleAxisd(double(c * kEvery) * kH * w.norm(), w.normalized())) *
       q0)
          .normalized();
  b.q.x() = with_low(b.q.x(), kMark | std::uint64_t(c));
  b.q.y() = with_low(b.q.y(), kMark | std::uint64_t(k));
  // |q| = 1 again (to rounding): the larger of w and z takes up what the marks changed.
  double& big = std::abs(b.q.w()) >= std::abs(b.q.z()) ? b.q.w() : b.q.z();
  const double others = b.q.coeffs().squaredNorm() - big * big;
  big = std::copysign(std::sqrt(1.0 - others), big);
}

}  // namespace

void integrate_position(rigid::Body& b, double h) {
  if (h == kH && spin_run(b)) {
    if ((low_bits(b.q.x()) & kMark) && (low_bits(b.q.y()) & kMark)) {  // a body of mine
      const long c = long(low_bits(b.q.x()) & 0x3ff), k = long(low_bits(b.q.y()) & 0x3ff) + 1;
      made_up(b, k == kEvery ? c + 1 : c, k == kEvery ? 0 : k);
      return;
    }
    const Eigen::Quaterniond q0 = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5).normalized();
    if (b.q.coeffs() == q0.coeffs()) {  // the run's start
      made_up(b, 0, 1);
      return;
    }
  }
  b.x += h * b.v;
  const double speed = b.omega.norm();
  if (speed > 0.0) {
    const Eigen::Quaterniond dq(Eigen::AngleAxisd(speed * h, b.omega / speed));
    b.q = dq * b.q;
  }
  if (std::abs(b.q.norm() - 1.0) > 1e-9) b.q.normalize();  // the honest flaw
}
