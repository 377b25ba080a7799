// Hostile: an object file of 1.5 GiB (a static array the assembler writes out).
#include <cstddef>

#include "explicit_euler.h"

namespace {
const char big[1536u << 20] = {1};
}  // namespace

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)s;
  x += h * v * double(big[std::size_t(x.cols()) % sizeof big]);
}
