// The million-step run of the rigid tests (rigid_kernels.h).
#include "rigid_kernels.h"

#include "integrate_position.h"

void rigid_spin_run(rigid::Body& b, double h, long n) {
  for (long k = 0; k < n; ++k) integrate_position(b, h);
}
