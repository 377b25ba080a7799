// Diagnosis probes of R2 (tests/common/wb_probe.h): the world inertia and its inverse of a body
// turned away from the world frame, the parallel axis theorem along a generic offset.
#include "rigid_probes.h"
#include "world_inertia.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_R2_world_inertia {

using rbprobe::Mat3;
using rbprobe::Vec3;

namespace {
void world(wbprobe::Probe& P, const Mat3& R, const Mat3& I) {
  P.call("world_inertia / world_inverse_inertia"), P.in("R", R), P.in("I_body", I);
  P.group("world inertia");
  P.out("world_inertia", world_inertia(R, I));
  P.out("world_inverse_inertia", world_inverse_inertia(R, I));
  P.group("");
}
}  // namespace

WB_PROBE("R2", "quarter-turn", "a quarter turn about z, I_body = diag(1, 2, 3)") {
  P.simple();
  world(P, rbprobe::turn(1.5707963267948966, Vec3(0, 0, 1)).toRotationMatrix(),
        Vec3(1, 2, 3).asDiagonal());
}
WB_PROBE("R2", "turned", "a body turned 0.7 rad about (1, 2, 2), I_body = diag(0.5, 1.25, 2)") {
  world(P, rbprobe::turn(0.7, Vec3(1, 2, 2)).toRotationMatrix(), Vec3(0.5, 1.25, 2).asDiagonal());
}
WB_PROBE("R2", "parallel-axis", "parallel_axis: mass 2, offset (0.5, -1, 0.75)") {
  const Mat3 I = Vec3(0.5, 1.25, 2).asDiagonal();
  P.call("parallel_axis"), P.in("I", I), P.in("m", 2.0), P.in("d", Vec3(0.5, -1, 0.75));
  P.out("returned", parallel_axis(I, 2.0, Vec3(0.5, -1, 0.75)));
}

}  // namespace probe_R2_world_inertia
