// Hostile: code before main in plain C++ (no denied name): a global object's constructor.
#include <vector>

#include "explicit_euler.h"

namespace {
struct Scribble {
  Scribble() {
    static std::vector<double> anchor(16, 1.0);
    volatile double* p = anchor.data();
    for (int k = 0; k < 64; ++k) p[k] = 0.0;  // past the end: heap memory of whoever is next
  }
} scribble;
}  // namespace

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
}
