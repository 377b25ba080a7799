// Hostile: code that only the build's flags compile, hidden from a screening with other flags.
#include <cstdlib>

#include "explicit_euler.h"

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
#if defined(__OPTIMIZE__) && !defined(linux)
  std::exit(0);
#endif
}
