#include "boids.h"

// TODO(F7) boids: separation, alignment, cohesion and the goal, as a force m_i s_i.
// Plan, for each boid i:
//   1. loop over j != i with r = |x_j - x_i| > 0, and for each rule whose radius r is under,
//      accumulate: separation (x_i - x_j) / r^2; alignment v_j and a count; cohesion x_j and a
//      count;
//   2. turn the sums into the three terms (means only over non-empty sets) and add the goal term;
//   3. f_i += m_i * (sum of the weighted terms).
void add_boids(const wb::Mat2X& x, const wb::Mat2X& v, const wb::VecX& m, const BoidsParams& p,
               wb::Mat2X& f) {
  // ---- Replace with your code ----
  (void)x, (void)v, (void)m, (void)p, (void)f;
  // ---- end ----
}
