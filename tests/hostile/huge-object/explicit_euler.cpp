// Hostile: an object file of 1.5 GiB.
#include "explicit_euler.h"

namespace {
struct Big {
  char bytes[1536u << 20];
};
constexpr Big make() {
  Big b{};
  b.bytes[0] = 1;
  return b;
}
const Big big = make();
}  // namespace

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)s;
  x += h * v * double(big.bytes[0]);
}
