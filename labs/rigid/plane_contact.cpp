#include "plane_contact.h"

#include <Eigen/Dense>

// TODO(R6) effective masses and the restitution target (see plane_contact.h).
// Plan: 1. c.r = c.p - x; I^-1 in the world frame (R2); c.K = E/m - [r]x I^-1 [r]x;
//       2. c.mass_n = 1 / (n^T K n);
//       3. vn = (v + omega x r).n; c.bias = -vn if vn > 0 (leaving), else -e vn if
//          -vn > threshold (an impact), else 0 (resting).
void prepare_contact(const rigid::Body& b, const rigid::Vec3& n, double e, double threshold,
                     Contact& c) {
  // ---- Replace with your code ----
  (void)b, (void)n, (void)e, (void)threshold, (void)c;
  // ---- end ----
}

// TODO(R6) apply the totals kept from the previous step (see plane_contact.h).
// Plan: J = Pn n + Pt; v += J / m; omega += I^-1 (r x J).
void warm_start_contact(rigid::Body& b, const Contact& c, const rigid::Vec3& n) {
  // ---- Replace with your code ----
  (void)b, (void)c, (void)n;
  // ---- end ----
}

// TODO(R6) one iteration on one contact: accumulate, clamp the totals (see plane_contact.h).
// Plan: 1. lambda = mass_n (bias - u.n); new total max(Pn + lambda, 0); apply the CHANGE of
//          the total along n; store the total;
//       2. u again, ut = its part in the plane; if |ut| > 0: d = ut / |ut|,
//          Pt' = Pt - |ut| / (d^T K d) d; clamp |Pt'| <= mu * (the new total Pn);
//          apply the CHANGE Pt' - Pt; store Pt'; return the normal change.
double solve_contact(rigid::Body& b, Contact& c, const rigid::Vec3& n, double mu) {
  // ---- Replace with your code ----
  (void)b, (void)c, (void)n, (void)mu;
  return 0.0;
  // ---- end ----
}

// TODO(R6) every contact of a body with a plane, together (see plane_contact.h).
// Plan: prepare every contact; warm start every contact; `iterations` passes of
//       solve_contact over them; return the sum of the Pn.
double solve_plane_contacts(rigid::Body& b, std::vector<Contact>& contacts, const rigid::Vec3& n,
                            double e, double threshold, double mu, int iterations) {
  // ---- Replace with your code ----
  (void)b, (void)contacts, (void)n, (void)e, (void)threshold, (void)mu, (void)iterations;
  return 0.0;
  // ---- end ----
}
