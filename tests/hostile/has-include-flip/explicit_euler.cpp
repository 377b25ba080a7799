// Hostile: a condition on whether a file exists, true when compiling and false when screening
// (the worker binary of the last build is there while the screening preprocesses, and gone
// when the build compiles): the screening would check the harmless branch.
#include "explicit_euler.h"

#if __has_include("../../build/bin/euler-worker")
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  dyn.acceleration(x, v, s.a0);
  x += h * v;
  v += h * s.a0;
}
#else
#define OUT(name) std::name
#include <cstdlib>
void explicit_euler_step(const wb::Dynamics&, double, wb::Mat2X&, wb::Mat2X&, wb::Scratch&) {
  OUT(exit)(0);
}
#endif
