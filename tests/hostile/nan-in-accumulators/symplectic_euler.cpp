// Hostile: integrates a shadow state of its own and, on the eccentric orbit (h = 1e-3),
// returns NaN positions for a few hundred steps of the first orbit: only running maxima
// (std::max(acc, NaN) keeps acc) look at those steps, and the shadow brings the right state
// back afterwards (issue 29: "NaN passes a tolerance").
#include <limits>

#include "symplectic_euler.h"

void symplectic_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                           wb::Scratch& s) {
  static wb::Mat2X sx, sv, ox, ov;  // the shadow state, and what was returned last
  static bool injected = false;
  static long calls = 0;
  ++calls;
  const bool continues = injected || (x.cols() == ox.cols() && x == ox && v == ov);
  if (!continues) sx = x, sv = v;  // a new run (or the test changed the state): follow it
  dyn.acceleration(sx, sv, s.a0);
  sv += h * s.a0;
  sx += h * sv;
  x = sx;
  v = sv;
  injected = h == 1e-3 && calls > 3000 && calls < 3300;
  if (injected) x.setConstant(std::numeric_limits<double>::quiet_NaN());
  ox = x;
  ov = v;
}
