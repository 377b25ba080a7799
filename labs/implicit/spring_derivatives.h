// TODO(I2) the spring's force and derivatives. Handout: handouts/implicit.md#i2.
// Tests: [I2].
#pragma once
#include "wb/types.h"

// The force on end i of a damped spring (as in the forces lab, F5) and its
// derivatives with respect to end i's position and velocity:
//
//   d = x_i - x_j,  L = |d|,  u = d / L,  P = u u^T  (projection on the spring)
//   f = -( k (L - rest) + kd (v_i - v_j) . u ) u
//   K = df_el/dx_i = -k ( P + (1 - rest/L) (I - P) )       (elastic part only)
//   D = df/dv_i    = -kd P
//
// The other blocks follow: df_i/dx_j = -K, df_j/dx_i = -K, df_j/dx_j = K (and
// the same for D), because f_j = -f_i and f depends on x_i - x_j only.
// K leaves out how the damping term turns with u (Baraff and Witkin 1998 do
// too), so that K and D are symmetric.
//
// A compressed spring (L < rest) has 1 - rest/L < 0: K then has a positive
// eigenvalue across the spring and the step's matrix may be indefinite. With
// `definite` true the factor (1 - rest/L) is replaced by max(0, 1 - rest/L),
// which keeps -K positive semi-definite (a standard fix; Newton then converges
// more slowly on compressed springs, but the solve never breaks down).
//
// When L == 0 the direction u is undefined: f = 0, K = -k I, D = 0.
//
// Inputs:
//   xi, xj    end positions (m)
//   vi, vj    end velocities (m/s)
//   k, rest   stiffness (N/m) >= 0, rest length (m) >= 0
//   kd        damping along the spring (N s/m) >= 0
//   definite  clamp the compressive term (see above)
// Outputs:
//   f  force on end i (N)
//   K  2 x 2 block df_i/dx_i (N/m), symmetric
//   D  2 x 2 block df_i/dv_i (N s/m), symmetric
void spring_derivatives(const wb::Vec2& xi, const wb::Vec2& xj, const wb::Vec2& vi,
                        const wb::Vec2& vj, double k, double rest, double kd, bool definite,
                        wb::Vec2& f, wb::Mat2& K, wb::Mat2& D);
