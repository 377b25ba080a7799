// TODO(C4) Coulomb friction at a contact. Handout: handouts/collisions.md#c4. Tests: [C4].
#pragma once
#include "wb/types.h"

// Friction at a particle-plane contact, applied right after the normal impulse
// jn (from collide_plane) with unit normal n. Coulomb's law bounds the
// tangential impulse by mu jn (the friction cone):
//
//   v_t = v - (v.n) n                       tangential velocity (m/s)
//   static  (m |v_t| <= mu jn):  v = v - v_t                 impulse m |v_t|
//   sliding (m |v_t| >  mu jn):  v = v - (mu jn / m) v_t / |v_t|   impulse mu jn
//
// The normal velocity is untouched; with v_t = 0 nothing changes (no NaN).
//
// Inputs:
//   n    unit contact normal
//   jn   normal impulse magnitude (N s, >= 0) of this contact, this step
//   mu   friction coefficient (>= 0)
//   m    particle mass (kg, > 0)
// Outputs:
//   v    velocity (m/s), changed in place
// Returns the tangential impulse magnitude applied (N s).
double friction_impulse(const wb::Vec2& n, double jn, double mu, double m, wb::Vec2& v);
