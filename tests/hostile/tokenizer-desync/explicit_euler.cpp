// Hostile: desynchronises a naive tokenizer to hide a #line directive.
// The spacing is the attack:
// clang-format off
#include <cstdlib>

#include "explicit_euler.h"

#define IGNORE(...)
IGNORE(xR"(a")
static const int kCount = 1'000'000;  // ' "
#line 1 "/usr/include/stdlib.h"
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s, (void)kCount;
  std::exit(0);
}
IGNORE(")")
