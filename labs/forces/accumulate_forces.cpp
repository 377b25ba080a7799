#include "accumulate_forces.h"

// TODO(F6) accumulate all forces: make f 2 x n and zero, then let every term add to it.
void accumulate_forces(const std::vector<std::unique_ptr<wb::Force>>& forces, const wb::Mat2X& x,
                       const wb::Mat2X& v, const wb::VecX& m, wb::Mat2X& f) {
  // ---- Replace with your code ----
  (void)forces, (void)x, (void)v, (void)m, (void)f;
  // ---- end ----
}
