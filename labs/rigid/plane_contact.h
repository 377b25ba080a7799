// TODO(R6) contact with a plane by accumulated impulses: restitution above a
// closing speed, Coulomb friction, warm starting. Handout: handouts/rigid.md#r6.
// Tests: [R6].
#pragma once
#include <vector>

#include "rigid_body.h"

//                 omega
//          +-------(.)----+
//          |       x      |       r = p - x        (centre -> contact point)
//          |        \ r   |       u = v + omega x r  (velocity of the point)
//   _______|_________\p___|____   n (plane normal, unit, out of the plane)
//
// An impulse J at p changes v by J / m and omega by I^-1 (r x J) (I^-1 in the world
// frame, R2), so u by K J with the 3x3 matrix
//
//   K = E / m - [r]x I^-1 [r]x          (symmetric positive definite; [r]x = skew(r))
//
// Along a unit direction d alone, u.d changes by d^T K d per unit impulse: the
// EFFECTIVE MASS along d is 1 / (d^T K d) (kg); along n it is mass_n = 1 / (n^T K n).
//
// A contact keeps its impulses as TOTALS: Pn along n, and Pt (a vector in the plane,
// Pt . n = 0): everything the body has received from this contact in this step
// (and, to start the next step, in the last one: warm starting). Coulomb's law and
// "the plane pushes, never pulls" bound the TOTALS, never one iteration's increment:
//
//   Pn >= 0,     |Pt| <= mu Pn
//
// prepare_contact: r = p - x, K, mass_n as above, and the normal velocity the
//   contact aims for, from u.n BEFORE any impulse of this step:
//     bias = -e (u.n)   when -(u.n) > threshold       (approaching fast: an impact bounces)
//     bias = 0          when 0 <= -(u.n) <= threshold (approaching slowly: resting)
//     bias = -(u.n)     when u.n > 0                  (leaving: the other contacts may turn
//                                                      it back, never faster than it leaves)
//   An impulse that takes the point from u.n to u.n' changes the kinetic energy by
//   (1/2) P (u.n + u.n') (P its total): -e u.n loses (1 - e) of it, 0 loses it, and -u.n for
//   a leaving point turned back keeps it (a target of 0 would ADD (1/2) P u.n).
//   Pn, Pt are left as they are (the caller keeps them from the previous step).
//
// warm_start_contact: applies the stored totals at p, J = Pn n + Pt.
//
// solve_contact: ONE iteration on one contact, from the body's current v, omega:
//   1. normal:   lambda = mass_n (bias - u.n);  Pn' = max(Pn + lambda, 0);
//                apply (Pn' - Pn) n at p;  Pn = Pn'
//   2. friction: with u AFTER step 1, its sliding part ut = u - (u.n) n; when |ut| > 0
//                (else nothing: no NaN), d = ut / |ut| and
//                  Pt' = Pt - |ut| / (d^T K d) d;   if |Pt'| > mu Pn, scale Pt' to length mu Pn
//                (Pn the new total of step 1); apply Pt' - Pt at p; Pt = Pt'
//                (at the end the friction opposes the sliding, as Coulomb's law says)
//   Returns Pn' - Pn of step 1, the normal impulse this iteration added (N s).
//
// solve_plane_contacts: the contacts of one body with one plane (every point that
//   touches it), resolved TOGETHER: prepare each, warm start each, then
//   `iterations` passes of solve_contact over the contacts in order.
//   Returns the sum of the contacts' Pn (N s).
//
// Penetration is not the solver's business: the caller pushes the body out after
// the velocities are solved, without changing them or the kinetic energy (split
// impulses, handout §R6).
//
// Inputs:
//   b          the body (m, I_body, x, v, q, omega)
//   c.p        contact point (m), world;  c.Pn, c.Pt  totals from the previous step
//   n          the plane's unit normal;  e  restitution in [0, 1]
//   threshold  closing speed (m/s, >= 0) below which a contact does not bounce
//   mu         friction coefficient >= 0;  iterations  >= 1
// Outputs:
//   b.v, b.omega (impulses); c.r, c.K, c.mass_n, c.bias (prepare_contact);
//   c.Pn, c.Pt (solve_contact)
struct Contact {
  rigid::Vec3 p = rigid::Vec3::Zero();   // contact point, world (m)
  double Pn = 0;                         // accumulated normal impulse (N s), >= 0
  rigid::Vec3 Pt = rigid::Vec3::Zero();  // accumulated friction impulse, in the plane (N s)
  // Set by prepare_contact:
  rigid::Vec3 r = rigid::Vec3::Zero();  // centre of mass -> p, world (m)
  rigid::Mat3 K = rigid::Mat3::Zero();  // velocity change of p per unit impulse at p (1/kg)
  double mass_n = 0;                    // effective mass along n (kg)
  double bias = 0;                      // normal velocity aimed for (m/s)
};

void prepare_contact(const rigid::Body& b, const rigid::Vec3& n, double e, double threshold,
                     Contact& c);
void warm_start_contact(rigid::Body& b, const Contact& c, const rigid::Vec3& n);
double solve_contact(rigid::Body& b, Contact& c, const rigid::Vec3& n, double mu);
double solve_plane_contacts(rigid::Body& b, std::vector<Contact>& contacts, const rigid::Vec3& n,
                            double e, double threshold, double mu, int iterations);
