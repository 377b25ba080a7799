#include "vortex.h"

// TODO(F8) vortex field: the Rankine flow u(x) and the drag c (u(x_i) - v_i) towards it.
wb::Vec2 vortex_flow(const wb::Vec2& x, const VortexParams& p) {
  // ---- Replace with your code ----
  (void)x, (void)p;
  return wb::Vec2::Zero();
  // ---- end ----
}

void add_vortex(const wb::Mat2X& x, const wb::Mat2X& v, const VortexParams& p, wb::Mat2X& f) {
  // ---- Replace with your code ----
  (void)x, (void)v, (void)p, (void)f;
  // ---- end ----
}
