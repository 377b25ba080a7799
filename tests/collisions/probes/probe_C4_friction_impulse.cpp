// Diagnosis probes of C4 (tests/common/wb_probe.h): static friction, sliding, the edge of the
// cone, no sliding; on a tilted normal with a normal velocity, so that the tangential part
// shows.
#include <cmath>

#include "friction_impulse.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_C4_friction_impulse {

namespace {
using wb::Vec2;
void run(wbprobe::Probe& P, const Vec2& n, double jn, double mu, double m, Vec2 v) {
  P.call("friction_impulse");
  P.in("n", n), P.in("jn", jn), P.in("mu", mu), P.in("m", m), P.in("v", v);
  const double j = friction_impulse(n, jn, mu, m, v);
  P.out("returned", j), P.out("v", v);
}
const Vec2 kN(0.6, 0.8), kT(-0.8, 0.6);
}  // namespace

WB_PROBE("C4", "floor-slide", "mass 1 sliding at 2 m/s on a floor, mu jn = 0.5") {
  P.simple();
  run(P, Vec2(0, 1), 1, 0.5, 1, Vec2(2, 0));
}
// Inside the cone (m |v_t| = 0.75 <= mu jn = 1, with |v_t| = 1.5 > 1): it stops sliding.
WB_PROBE("C4", "static", "mass 0.5 sliding at 1.5 m/s on a tilted plane, mu jn = 1: it sticks") {
  P.simple();
  run(P, kN, 2, 0.5, 0.5, 1.5 * kT + 0.3 * kN);
}
// Outside the cone (m |v_t| = 0.8 > mu jn = 0.5, with |v_t| = 0.2 < 0.5): it slides.
WB_PROBE("C4", "sliding", "mass 4 sliding at 0.2 m/s on a tilted plane, mu jn = 0.5: it slides") {
  P.simple();
  run(P, kN, 1, 0.5, 4, 0.2 * kT + 0.3 * kN);
}
// On the edge of the cone (m |v_t| = mu jn = 1): static.
WB_PROBE("C4", "edge", "mass 2 sliding at 0.5 m/s on a floor, mu jn = 1 exactly: it sticks") {
  P.simple();
  run(P, Vec2(0, 1), 2, 0.5, 2, Vec2(0.5, 0.25));
}
// No sliding and no normal impulse: the cone is a point (m |v_t| = mu jn = 0), still static.
WB_PROBE("C4", "no-slide-no-push",
         "moving only along a floor's normal with jn = 0 (m |v_t| = mu jn = 0): nothing "
         "changes") {
  P.simple();
  run(P, Vec2(0, 1), 0, 0.5, 2, Vec2(0, -0.3));
}
// The cone, in one output: inside it, outside it, on its edge and at its tip (at rest with no
// normal impulse: m |v_t| = mu jn = 0, still static), each column the impulse and v. Every
// mistake in the cone test shows here, the tip's strict comparison too. Apart, column by
// column: whether v changed by the impulse returned (m |v' - v| - j, 0 for any correct code:
// the header's "impulse magnitude applied"). A mistake of the cone (the wrong case, the wrong
// bound) is wrong in both, yet consistent; one in applying the impulse (a velocity change
// without the 1/m, not along v_t / |v_t|) breaks that consistency: it is not the cone's. Where
// v is not finite the gap is recorded as 0: the NaN shows in v, and belongs to the cone's tip.
WB_PROBE("C4", "cone",
         "four contacts on a tilted plane: m |v_t| inside, outside and on the edge of the cone "
         "mu jn, and at its tip (at rest, jn = 0)") {
  P.call("friction_impulse");
  struct Case {
    double jn, mu, m;
    Vec2 v;
  };
  const Case cs[] = {{2, 0.5, 0.5, 1.5 * kT + 0.3 * kN},
                     {1, 0.5, 4, 0.2 * kT + 0.3 * kN},
                     {2, 0.5, 2, 0.5 * kT + 0.25 * kN},
                     {0, 0.5, 2, Vec2(0, 0)}};
  Eigen::MatrixXd in(5, 4), out(3, 4), agree(1, 4);
  for (int k = 0; k < 4; ++k) {
    Vec2 v = cs[k].v;
    in.col(k) << cs[k].jn, cs[k].mu, cs[k].m, v;
    const double j = friction_impulse(kN, cs[k].jn, cs[k].mu, cs[k].m, v);
    out.col(k) << j, v;
    const double gap = cs[k].m * (v - cs[k].v).norm() - j;
    agree(0, k) = std::isfinite(gap) ? gap : 0.0;  // a NaN shows in v itself
  }
  P.in("n", kN), P.in("each column: jn, mu, m, v", in);
  P.out("each column: returned impulse, v", out);
  P.out_each("each column: m |v' - v| - returned impulse (0: v changed by that impulse)", agree);
}
// No sliding: nothing changes, no NaN.
WB_PROBE("C4", "no-slide", "moving only along the normal: nothing changes") {
  run(P, kN, 1, 0.5, 2, 0.3 * kN);
}

}  // namespace probe_C4_friction_impulse
