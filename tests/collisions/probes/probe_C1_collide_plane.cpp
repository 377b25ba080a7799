// Diagnosis probes of C1 (tests/common/wb_probe.h): an impact on a tilted plane, then one
// situation at a time: receding, just touching, the centre below the plane, a resting contact,
// an approach at exactly rest_speed, clear of the plane.
#include <vector>

#include "collide_plane.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_C1_collide_plane {

namespace {
using wb::Vec2;
void run(wbprobe::Probe& P, const Vec2& p, const Vec2& n, double r, double m, double e,
         double rest_speed, Vec2 x, Vec2 v) {
  P.call("collide_plane");
  P.in("p", p), P.in("n", n), P.in("r", r), P.in("m", m), P.in("restitution", e);
  P.in("rest_speed", rest_speed), P.in("x", x), P.in("v", v);
  const double j = collide_plane(p, n, r, m, e, rest_speed, x, v);
  P.group("the impulse");  // the impulse and the velocity go wrong together
  P.out("returned", j), P.out("v", v);
  P.group("");
  P.out("x", x);
}
// Several situations in one output: (j, x, v) of each, one column each.
struct Case {
  Vec2 p, n;
  double r, m, e, rest_speed;
  Vec2 x, v;
};
void cases(wbprobe::Probe& P, const std::vector<Case>& cs) {
  P.call("collide_plane");
  Eigen::MatrixXd in(12, Eigen::Index(cs.size())), out(5, Eigen::Index(cs.size()));
  for (std::size_t k = 0; k < cs.size(); ++k) {
    Case c = cs[k];
    in.col(Eigen::Index(k)) << c.p, c.n, c.r, c.m, c.e, c.rest_speed, c.x, c.v;
    const double j = collide_plane(c.p, c.n, c.r, c.m, c.e, c.rest_speed, c.x, c.v);
    out.col(Eigen::Index(k)) << j, c.x, c.v;
  }
  P.in("each column: p, n, r, m, restitution, rest_speed, x, v", in);
  P.out("each column: returned j, x, v", out);
}
const Vec2 kP(1, -0.5);
const Vec2 kN(0.6, 0.8);  // a tilted plane
}  // namespace

WB_PROBE("C1", "floor", "a ball of mass 1 sinking 0.05 into a floor at 2 m/s, e = 0.5") {
  P.simple();
  run(P, Vec2(0, 0), Vec2(0, 1), 0.1, 1, 0.5, 0.01, Vec2(0, 0.05), Vec2(0, -2));
}
// The impact: impulse and push-out.
WB_PROBE("C1", "impact",
         "mass 2 sinking 0.05 into a tilted plane, approaching fast and sliding, e = 0.6") {
  run(P, kP, kN, 0.25, 2, 0.6, 0.1, kP + 0.2 * kN + 1.5 * Vec2(-0.8, 0.6),
      -3 * kN + 1.25 * Vec2(-0.8, 0.6));
}
// The same impact with e = 0: every mistake of the impulse formula shows, none in the choice
// of e (resting or bouncing) can, so a mistake in that choice is not taken for the impulse's.
WB_PROBE("C1", "impact-inelastic",
         "the same impact with e = 0: the normal velocity stops, the sliding goes on") {
  run(P, kP, kN, 0.25, 2, 0, 0.1, kP + 0.2 * kN + 1.5 * Vec2(-0.8, 0.6),
      -3 * kN + 1.25 * Vec2(-0.8, 0.6));
}
// Receding: pushed out, no impulse.
WB_PROBE("C1", "receding", "sinking 0.05 into the tilted plane but moving away from it") {
  P.simple();
  run(P, kP, kN, 0.25, 2, 0.6, 0.1, kP + 0.2 * kN, 1.5 * kN + Vec2(-0.8, 0.6));
}
// Just touching (gap 0), approaching: a contact.
WB_PROBE("C1", "touching", "just touching a floor (gap 0) and approaching at 2 m/s") {
  P.simple();
  run(P, Vec2(0, 0), Vec2(0, 1), 0.25, 2, 0.6, 0.1, Vec2(0.5, 0.25), Vec2(0.5, -2));
}
// The centre below the plane, deeper than the radius.
WB_PROBE("C1", "deep", "the centre 0.35 below a floor (radius 0.1), approaching") {
  P.simple();
  run(P, Vec2(0, 0), Vec2(0, 1), 0.1, 2, 0.6, 0.1, Vec2(0.5, -0.35), Vec2(0.5, -2));
}
// Resting: the approach is slower than rest_speed, the sliding is not.
// A resting contact alone (an impulse that only stops the approach, e or not); a detail of the
// resting part, whose probe is "rest" below (every case of it, the threshold included).
WB_PROBE("C1", "resting",
         "sinking into a floor, approaching at 0.05 m/s (rest_speed 0.1), sliding at 2 m/s") {
  P.simple();
  run(P, Vec2(0, 0), Vec2(0, 1), 0.25, 2, 0.6, 0.1, Vec2(0.5, 0.2), Vec2(2, -0.05));
}
// The approach at exactly rest_speed bounces.
WB_PROBE("C1", "threshold", "approaching a floor at exactly rest_speed = 0.25: it bounces") {
  P.simple();
  run(P, Vec2(0, 0), Vec2(0, 1), 0.25, 2, 0.5, 0.25, Vec2(0.5, 0.2), Vec2(0, -0.25));
}
// When there is a contact: clear, just touching, receding, the centre below the plane.
WB_PROBE("C1", "contact",
         "four situations: 0.3 above, just touching, sinking in but receding, the centre 0.35 "
         "below (radius 0.1)") {
  const Vec2 o(0, 0), up(0, 1);
  cases(P, {{o, up, 0.25, 2, 0.6, 0.1, Vec2(0.5, 0.55), Vec2(0.5, -2)},
            {o, up, 0.25, 2, 0.6, 0.1, Vec2(0.5, 0.25), Vec2(0.5, -2)},
            {kP, kN, 0.25, 2, 0.6, 0.1, kP + 0.2 * kN, 1.5 * kN + Vec2(-0.8, 0.6)},
            {o, up, 0.1, 2, 0.6, 0.1, Vec2(0.5, -0.35), Vec2(0.5, -2)}});
}
// When a contact rests: approaching slower than rest_speed (sliding fast), at rest_speed, faster.
WB_PROBE("C1", "rest",
         "three approaches to a floor (rest_speed 0.25): at 0.05 m/s sliding at 2 m/s, at "
         "exactly 0.25, at 0.5") {
  const Vec2 o(0, 0), up(0, 1);
  cases(P, {{o, up, 0.25, 2, 0.6, 0.25, Vec2(0.5, 0.2), Vec2(2, -0.05)},
            {o, up, 0.25, 2, 0.5, 0.25, Vec2(0.5, 0.2), Vec2(0, -0.25)},
            {o, up, 0.25, 2, 0.5, 0.25, Vec2(0.5, 0.2), Vec2(0, -0.5)}});
}
// Clear of the plane: nothing.
WB_PROBE("C1", "clear", "0.3 above a floor, approaching: nothing happens yet") {
  P.simple();
  run(P, Vec2(0, 0), Vec2(0, 1), 0.25, 2, 0.6, 0.1, Vec2(0.5, 0.55), Vec2(0.5, -2));
}

}  // namespace probe_C1_collide_plane
