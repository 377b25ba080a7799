// TODO(C5) contacts resolved together by accumulated, warm-started impulses.
// Handout: handouts/collisions.md#c5. Tests: [C5].
#pragma once
#include "wb/types.h"

// One contact of particle a with particle b, or with a plane (b = -1):
//
//        ( a ) <-- n -- ( b )     or     ( a )
//                                    ------n------ plane      n: unit, from b (or the
//                                                                plane) towards a
//   u  = v_a - v_b   (v_b = 0 for a plane)     relative velocity (m/s)
//   un = u.n  (< 0: closing),   ut = u.t with t = wb::perp(n)  (sliding)
//
// An impulse P along a unit direction d changes v_a by w_a P d and v_b by -w_b P d
// (w = 1/m, the inverse masses; w_b = 0 for a plane), so u.d by (w_a + w_b) P: the
// effective mass along n, and along t too, is
//   mass_n = 1 / (w_a + w_b)
//
// The contact keeps its impulses as TOTALS: Pn along n and Pt along t, all that it
// has given in this step (and, to start the next step, in the last one: warm
// starting). The bounds are on the TOTALS, never on one iteration's increment:
//   Pn >= 0 (a contact pushes, never pulls),   |Pt| <= mu Pn (Coulomb)
//
// prepare_contact: mass_n, and the normal velocity the contact aims for, from un
//   BEFORE any impulse of this step:
//     bias = -e un   when -un > threshold       (closing fast: an impact bounces)
//     bias = 0       when 0 <= -un <= threshold (closing slowly: resting, no micro-bounce)
//     bias = -un     when un > 0                (separating: the other contacts may turn
//                                                it back, never faster than it leaves)
//   An impulse that takes a contact from un to un' changes the kinetic energy by
//   (1/2) P (un + un') (P its total): -e un loses (1 - e) of it, 0 loses it, and -un for a
//   separating contact turned back keeps it (a target of 0 would ADD (1/2) P un).
//   Pn, Pt are left as they are (kept by the caller from the last step).
// warm_start_contact: applies the stored totals, J = Pn n + Pt t: v_a += w_a J,
//   v_b -= w_b J (nothing for a plane).
// solve_contact: ONE iteration, from the current velocities:
//   1. lambda = mass_n (bias - un);  Pn' = max(Pn + lambda, 0);  apply (Pn' - Pn) n
//   2. with un, ut AFTER step 1:  Pt' = Pt - mass_n ut, clamped to [-mu Pn', mu Pn'];
//      apply (Pt' - Pt) t
//   stores Pn', Pt'; returns Pn' - Pn, the normal impulse this iteration added (N s).
//
// The framework (framework/drivers/collisions/contact_world.cpp) finds the contacts and
// keeps their totals from step to step. Impacts first, one at a time: for `iterations`
// passes, each contact with e > 0 gets prepare_contact with no totals on the current
// velocities and, if it closes faster than the threshold (bias > 0), ONE solve_contact:
// the restitution law on its own approach, as C1 and C2 apply it, which keeps an elastic
// impact's energy whatever else the contact touches. Then every contact together:
// prepare, warm start, `iterations` passes of solve_contact. What overlap is left is
// removed by moving positions only (no velocity: it adds no energy).
//
// Inputs:
//   w          inverse masses 1/m (1/kg), one per particle, > 0
//   v          2 x n velocities (m/s)
//   e          restitution in [0, 1];  threshold  closing speed (m/s) >= 0
//   c          the contact (a, b, n, mu; Pn, Pt from the last step)
// Outputs:
//   v          columns a and b changed by the impulses
//   c.mass_n, c.bias (prepare_contact);  c.Pn, c.Pt (solve_contact)
struct Contact {
  int a = 0;                    // particle
  int b = -1;                   // the other particle, or -1 for a plane
  wb::Vec2 n = wb::Vec2(0, 1);  // unit normal, from b (or the plane) towards a
  double mu = 0;                // friction coefficient, >= 0
  double Pn = 0;                // accumulated normal impulse (N s), >= 0
  double Pt = 0;                // accumulated friction impulse along t = perp(n) (N s)
  double mass_n = 0;            // 1 / (w_a + w_b) (kg), set by prepare_contact
  double bias = 0;              // normal velocity aimed for (m/s), set by prepare_contact
};

void prepare_contact(const wb::VecX& w, const wb::Mat2X& v, double e, double threshold,
                     Contact& c);
void warm_start_contact(const wb::VecX& w, const Contact& c, wb::Mat2X& v);
double solve_contact(const wb::VecX& w, Contact& c, wb::Mat2X& v);
