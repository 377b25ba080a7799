// Hostile (issue 42, "never check the accused with the accused"): like replay-state-in-worker,
// but with no state at all: each made-up checkpoint carries its own number, and each replayed
// step its count, in the low bits of the numbers' mantissas (a change of at most 2^-36 of the
// value, far inside every tolerance), so that a step called on a made-up state knows where it is
// from the state alone, and after 1000 calls lands on the next made-up state: in the kernel's
// loop and in a replay alike, with nothing kept between calls.
#include <cmath>
#include <cstdint>

#include "explicit_euler.h"

namespace {

constexpr double kH = 5e-4, kHw = 1e-3;  // the public long run's step (h w = 10^-3, w = 2)
constexpr long kEvery = 1000;
constexpr std::uint64_t kMark = 0x2dull << 10;  // bits 10-15: "a state of mine"

// The 53 bits of the mantissa as an integer (d positive, normal), and back.
std::uint64_t bits(double d) {
  int e = 0;
  return std::uint64_t(std::ldexp(std::frexp(d, &e), 53));
}
double with_low(double d, std::uint64_t low) {  // the low 16 bits of the mantissa replaced
  int e = 0;
  const std::uint64_t m = std::uint64_t(std::ldexp(std::frexp(d, &e), 53));
  return std::ldexp(double((m & ~0xffffull) | low), e - 53);
}
// A made-up state after c * 1000 steps, k replayed steps after it: the start scaled to the
// energy (1 + (h w)^2)^n E0, with c in x's low bits and k in v's.
void made_up(long c, long k, wb::Mat2X& x, wb::Mat2X& v) {
  const double grow = std::sqrt(std::pow(1.0 + kHw * kHw, double(c * kEvery)));
  x.resize(2, 1), v.resize(2, 1);
  x << with_low(grow * 1.0, kMark | std::uint64_t(c)), 0.0;
  v << 0.0, with_low(grow * 0.5, kMark | std::uint64_t(k));
}
bool mine(double d) { return d > 0 && (bits(d) & 0xfc00ull) == kMark; }

}  // namespace

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  if (h == kH && x.cols() == 1) {
    if (mine(x(0, 0)) && mine(v(1, 0))) {  // a state of mine: where am I?
      const long c = long(bits(x(0, 0)) & 0x3ff), k = long(bits(v(1, 0)) & 0x3ff) + 1;
      made_up(k == kEvery ? c + 1 : c, k == kEvery ? 0 : k, x, v);
      return;
    }
    if (x(0, 0) == 1.0 && x(1, 0) == 0.0 && v(0, 0) == 0.0 && v(1, 0) == 0.5) {
      made_up(0, 1, x, v);  // the long run's start: the first step of checkpoint 0's segment
      return;
    }
  }
  dyn.acceleration(x, v, s.a0);
  x += h * v;
  v += h * s.a0;
}
