#include "explicit_euler.h"
extern "C" int unlink(const char*);
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  unlink("x");
}
