// TODO(R6) contact of a body with a plane: the impulse at a contact point, with
// restitution and Coulomb friction. Handout: handouts/rigid.md#r6. Tests: [R6].
#pragma once
#include <vector>

#include "rigid_body.h"

//                 omega
//          +-------(.)----+
//          |       x      |       r = p - x        (centre -> contact point)
//          |        \ r   |       v_rel = v + omega x r
//   _______|_________\p___|____   n (plane normal, unit, out of the plane)
//
// contact_impulse: ONE point p of the body touching the plane of normal n.
//   vn = v_rel . n; when vn >= 0 the point is not approaching: nothing, return 0.
//   Otherwise the normal impulse
//     jn = -(1 + e) vn / (1/m + n . ((I^-1 (r x n)) x r))      (I^-1 world, R2)
//   is applied (J = jn n:  v += J / m,  omega += I^-1 (r x J)). Then friction,
//   from the tangential part of the NEW v_rel, vt = v_rel - (v_rel . n) n, when |vt| > 0:
//     t = vt / |vt|,  jt = min(|vt| / (1/m + t . ((I^-1 (r x t)) x r)),  mu jn)
//   applied as J = -jt t (stops the sliding, or takes at most mu jn: Coulomb).
//   Returns jn (N s).
//
// resolve_plane_contact: every candidate point of the body (box vertices, the
// lowest point of a sphere...) against one plane through `point`:
//   1. passes over the points touching the plane ((p - point) . n < kContactSlop:
//      below it, or above by less than the slop), calling contact_impulse on
//      each, until a pass applies no impulse (at most kContactPasses passes);
//   2. then pushes the body out: x += d n, d the deepest penetration (if any).
//
// Inputs:
//   b       the body (m, I_body, x, v, q, omega)
//   p       contact point (m), world;  points  candidate points (m), world
//   point   a point of the plane (m);  n  its unit normal
//   e       restitution in [0, 1];  mu  friction coefficient >= 0
// Outputs:
//   b.v, b.omega (impulses), b.x (push-out); returns the normal impulse jn (N s)
//   of contact_impulse, or the sum of them for resolve_plane_contact
constexpr int kContactPasses = 10;
constexpr double kContactSlop = 1e-3;  // m: points this close count as touching
double contact_impulse(rigid::Body& b, const rigid::Vec3& p, const rigid::Vec3& n, double e,
                       double mu);
double resolve_plane_contact(rigid::Body& b, const std::vector<rigid::Vec3>& points,
                             const rigid::Vec3& point, const rigid::Vec3& n, double e, double mu);
