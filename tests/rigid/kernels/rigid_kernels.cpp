// The million-step run of the rigid tests (rigid_kernels.h).
#include "rigid_kernels.h"

#include "integrate_position.h"

void rigid_spin_run(rigid::Body& b, double h, long n, long every,
                    std::vector<rigid::Body>& states) {
  states.assign(1, b);
  for (long k = 1; k <= n; ++k) {
    integrate_position(b, h);
    if (every > 0 && k % every == 0) states.push_back(b);
  }
}
