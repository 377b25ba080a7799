// Closed-form motions used as the reference of sweep mode (docs/sweep.md):
// a particle on a zero-rest-length spring to an anchor, and a particle
// around a point attractor (Kepler's problem, bound orbits).
#pragma once
#include "wb/types.h"

namespace wb {

// x'' = -w^2 (x - c):  x(t) = c + (x0 - c) cos wt + v0/w sin wt.
//   c: anchor (m); w = sqrt(k/m) > 0 (rad/s); x0, v0: state at t = 0; t (s).
// Outputs x (m), v (m/s) at time t.
void oscillator_exact(const Vec2& c, double w, const Vec2& x0, const Vec2& v0, double t, Vec2& x,
                      Vec2& v);

// x'' = -GM (x - c) / |x - c|^3 from (x0, v0) at t = 0, for a bound orbit
// (energy 1/2 |v0|^2 - GM/|x0 - c| < 0) that is not radial (x0 - c) x v0 != 0.
// Circular and elliptic orbits alike: Kepler's equation is solved by Newton's
// method, and the state follows from Lagrange's f and g functions.
// Outputs x (m), v (m/s) at time t.
void kepler_exact(const Vec2& c, double GM, const Vec2& x0, const Vec2& v0, double t, Vec2& x,
                  Vec2& v);

// The eccentric anomaly E with E - e sin E = M, for 0 <= e < 1 (any M):
// safeguarded Newton iteration, to within a few ulps.
double kepler_eccentric_anomaly(double M, double e);

}  // namespace wb
