#include "friction_impulse.h"

// TODO(C4) Coulomb friction (see friction_impulse.h).
// Plan: 1. the tangential velocity v_t = v - (v.n) n and its length;
//       2. the impulse that would stop it, m |v_t|, and the bound mu jn;
//       3. inside the cone: remove v_t; outside: remove (mu jn / m) along v_t / |v_t|;
//       4. return the impulse magnitude applied.
double friction_impulse(const wb::Vec2& n, double jn, double mu, double m, wb::Vec2& v) {
  // ---- Replace with your code ----
  (void)n, (void)jn, (void)mu, (void)m, (void)v;
  return 0.0;
  // ---- end ----
}
