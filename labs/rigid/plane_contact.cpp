#include "plane_contact.h"

// TODO(R6) contact impulse with restitution and Coulomb friction (see plane_contact.h).
// Plan: 1. r = p - x, v_rel = v + omega x r, vn = v_rel . n; return 0 if vn >= 0;
//       2. I^-1 in the world frame (R2); jn from the formula; apply J = jn n;
//       3. recompute v_rel, its tangential part vt; if |vt| > 0, jt = min(..., mu jn);
//          apply -jt t; return jn.
double contact_impulse(rigid::Body& b, const rigid::Vec3& p, const rigid::Vec3& n, double e,
                       double mu) {
  // ---- Replace with your code ----
  (void)b, (void)p, (void)n, (void)e, (void)mu;
  return 0.0;
  // ---- end ----
}

// TODO(R6) every point of a body against a plane (see plane_contact.h).
// Plan: 1. up to kContactPasses passes: contact_impulse on each point touching the plane
//          ((p - point) . n < kContactSlop)
//          (recompute nothing else: the points move only in step 2), stop after a pass
//          that applied no impulse;
//       2. d = the largest (point - p) . n over the points; if d > 0, x += d n.
double resolve_plane_contact(rigid::Body& b, const std::vector<rigid::Vec3>& points,
                             const rigid::Vec3& point, const rigid::Vec3& n, double e,
                             double mu) {
  // ---- Replace with your code ----
  (void)b, (void)points, (void)point, (void)n, (void)e, (void)mu;
  return 0.0;
  // ---- end ----
}
