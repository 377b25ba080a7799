#include "contact_solver.h"

// TODO(C5) effective mass and the restitution target (see contact_solver.h).
// Plan: 1. c.mass_n = 1 / (w_a + w_b), w_b = 0 for a plane (c.b < 0);
//       2. un = (v_a - v_b).n; c.bias = -un if un > 0 (separating), else -e un if
//          -un > threshold (an impact), else 0 (resting).
void prepare_contact(const wb::VecX& w, const wb::Mat2X& v, double e, double threshold,
                     Contact& c) {
  // ---- Replace with your code ----
  (void)w, (void)v, (void)e, (void)threshold, (void)c;
  // ---- end ----
}

// TODO(C5) the totals of the last step, applied again (see contact_solver.h).
// Plan: J = Pn n + Pt perp(n); v_a += w_a J; v_b -= w_b J (if b >= 0).
void warm_start_contact(const wb::VecX& w, const Contact& c, wb::Mat2X& v) {
  // ---- Replace with your code ----
  (void)w, (void)c, (void)v;
  // ---- end ----
}

// TODO(C5) one iteration: accumulate, clamp the totals (see contact_solver.h).
// Plan: 1. lambda = mass_n (bias - un); new total max(Pn + lambda, 0); apply the CHANGE
//          of the total along n; store it;
//       2. ut again; Pt' = Pt - mass_n ut clamped to +-mu * (the new total Pn); apply the
//          CHANGE along perp(n); store it; return the normal change.
double solve_contact(const wb::VecX& w, Contact& c, wb::Mat2X& v) {
  // ---- Replace with your code ----
  (void)w, (void)c, (void)v;
  return 0.0;
  // ---- end ----
}
