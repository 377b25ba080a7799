#include "explicit_euler.h"
namespace {
constexpr long slow() {
  long s = 0;
  for (long i = 0; i < 200000; ++i)
    for (long j = 0; j < 200000; ++j) s += (i ^ j) & 1;
  return s;
}
constexpr long kSlow = slow();
}  // namespace
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  x(0, 0) += double(kSlow) * 0.0;
}
