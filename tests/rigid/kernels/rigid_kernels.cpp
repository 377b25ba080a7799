// The million-step run of the rigid tests (rigid_kernels.h).
#include "rigid_kernels.h"

#include "integrate_position.h"

void rigid_tumble_run(rigid::Body& b, double h, long n) {
  for (long k = 0; k < n; ++k) {
    b.omega = tumble_omega(double(k) * h);
    integrate_position(b, h);
  }
}
