#include "heun_drag.h"

// TODO(D1) Heun's step: advance x and v by one step of size h (see heun_drag.h).
// Plan: 1. a0 at the current state; 2. the Euler predictor x1, v1;
//       3. a1 at the predictor; 4. average the two slopes.
void heun_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v, wb::Scratch& s) {
  // ---- Replace with your code ----
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  // ---- end ----
}
