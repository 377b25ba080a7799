// Diagnosis probes of C2 (tests/common/wb_probe.h): an oblique impact of unequal discs, then one
// situation at a time: one particle moving away while the pair closes, radii that differ,
// receding, coincident centres.
#include <vector>

#include "collide_particles.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_C2_collide_particles {

namespace {
using wb::Vec2;
void run(wbprobe::Probe& P, double m1, double r1, double m2, double r2, double e, Vec2 x1,
         Vec2 v1, Vec2 x2, Vec2 v2) {
  P.call("collide_particles");
  P.in("m1", m1), P.in("r1", r1), P.in("m2", m2), P.in("r2", r2), P.in("restitution", e);
  P.in("x1", x1), P.in("v1", v1), P.in("x2", x2), P.in("v2", v2);
  const double J = collide_particles(m1, r1, m2, r2, e, x1, v1, x2, v2);
  P.group("the impulse");  // the impulse and the velocities go wrong together
  P.out("returned", J), P.out("v1", v1), P.out("v2", v2);
  P.group("the positions");
  P.out("x1", x1), P.out("x2", x2);
  P.group("");
}
// Several situations in one output: (J, x1, v1, x2, v2) of each, one column each.
struct Case {
  double m1, r1, m2, r2, e;
  Vec2 x1, v1, x2, v2;
};
void cases(wbprobe::Probe& P, const std::vector<Case>& cs) {
  P.call("collide_particles");
  Eigen::MatrixXd in(13, Eigen::Index(cs.size())), out(9, Eigen::Index(cs.size()));
  for (std::size_t k = 0; k < cs.size(); ++k) {
    Case c = cs[k];
    in.col(Eigen::Index(k)) << c.m1, c.r1, c.m2, c.r2, c.e, c.x1, c.v1, c.x2, c.v2;
    const double J = collide_particles(c.m1, c.r1, c.m2, c.r2, c.e, c.x1, c.v1, c.x2, c.v2);
    out.col(Eigen::Index(k)) << J, c.x1, c.v1, c.x2, c.v2;
  }
  P.in("each column: m1, r1, m2, r2, restitution, x1, v1, x2, v2", in);
  P.out("each column: returned J, x1, v1, x2, v2", out);
}
}  // namespace

WB_PROBE("C2", "head-on", "two equal discs (radius 0.5) meeting head-on at 1 m/s each, e = 1") {
  P.simple();
  run(P, 1, 0.5, 1, 0.5, 1, Vec2(-0.45, 0), Vec2(1, 0), Vec2(0.45, 0), Vec2(-1, 0));
}
// The impact: masses 1.5 and 0.5, radii 0.45, 0.1 of overlap, oblique.
WB_PROBE("C2", "impact",
         "discs of masses 1.5 and 0.5 overlapping 0.1 in an oblique impact, e = 0.6") {
  run(P, 1.5, 0.45, 0.5, 0.45, 0.6, Vec2(0.48, 0.64), Vec2(-1, -0.5), Vec2(0, 0), Vec2(0.5, 1));
}
// The pair closes although particle 1 moves away from particle 2.
WB_PROBE("C2", "chasing", "both moving the same way, particle 2 faster: the pair closes") {
  P.simple();
  run(P, 1.5, 0.3, 0.5, 0.6, 0.6, Vec2(0.48, 0.64), Vec2(0.3, 0.4), Vec2(0, 0), Vec2(1.2, 1.6));
}
// Radii that differ: in contact only through the larger radius.
WB_PROBE("C2", "radii", "radii 0.2 and 0.6, centres 0.7 apart: in contact, approaching") {
  P.simple();
  run(P, 1.5, 0.2, 0.5, 0.6, 0.6, Vec2(0.42, 0.56), Vec2(-1, -0.5), Vec2(0, 0), Vec2(0.5, 1));
}
// Receding: separated, no impulse.
WB_PROBE("C2", "receding", "overlapping 0.1 but moving apart: separated, no impulse") {
  P.simple();
  run(P, 1.5, 0.3, 0.5, 0.6, 0.6, Vec2(0.48, 0.64), Vec2(0.3, 0.4), Vec2(0, 0), Vec2(-0.5, 0.2));
}
// When there is a contact and an impulse: closing while one particle moves away, radii that
// differ, receding, apart.
WB_PROBE("C2", "contact",
         "five situations: both moving the same way but closing, radii 0.2 and 0.6 touching, "
         "receding, apart, radii 0.6 and 0.3 overlapping") {
  cases(P,
        {{1.5, 0.3, 0.5, 0.6, 0.6, Vec2(0.48, 0.64), Vec2(0.3, 0.4), Vec2(0, 0), Vec2(1.2, 1.6)},
         {1.5, 0.6, 0.5, 0.3, 0.6, Vec2(0.48, 0.64), Vec2(-1, -0.5), Vec2(0, 0), Vec2(0.5, 1)},
         {1.5, 0.2, 0.5, 0.6, 0.6, Vec2(0.42, 0.56), Vec2(-1, -0.5), Vec2(0, 0), Vec2(0.5, 1)},
         {1.5, 0.3, 0.5, 0.6, 0.6, Vec2(0.48, 0.64), Vec2(0.3, 0.4), Vec2(0, 0), Vec2(-0.5, 0.2)},
         {1.5, 0.3, 0.5, 0.6, 0.6, Vec2(0.72, 0.96), Vec2(-1, -0.5), Vec2(0, 0), Vec2(0.5, 1)}});
}
// Coincident centres: the fallback normal (0, 1).
WB_PROBE("C2", "coincident", "both centres at one point, approaching along y") {
  run(P, 1.5, 0.45, 0.5, 0.45, 0.6, Vec2(1, 1), Vec2(0.5, -1), Vec2(1, 1), Vec2(0, 1));
}

}  // namespace probe_C2_collide_particles
