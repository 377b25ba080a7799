#include "explicit_euler.h"
#define E2      \
  undeclared_a; \
  undeclared_b;
#define E4 E2 E2
#define E8 E4 E4
#define E16 E8 E8
#define E64 E16 E16 E16 E16
#define E256 E64 E64 E64 E64
#define E1K E256 E256 E256 E256
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  E1K E1K E1K E1K E1K E1K E1K E1K
}
