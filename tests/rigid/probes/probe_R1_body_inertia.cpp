// Diagnosis probes of R1 (tests/common/wb_probe.h): one shape per probe, edges that differ.
#include "body_inertia.h"
#include "rigid_probes.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_R1_body_inertia {

using rbprobe::Vec3;

WB_PROBE("R1", "cube", "box_inertia of a unit cube of mass 1") {
  P.simple();
  P.call("box_inertia"), P.in("m", 1.0), P.in("size", Vec3(1, 1, 1));
  P.out("returned", box_inertia(1.0, Vec3(1, 1, 1)));
}
WB_PROBE("R1", "box", "box_inertia: mass 3, edges 1, 2 and 4") {
  P.call("box_inertia"), P.in("m", 3.0), P.in("size", Vec3(1, 2, 4));
  P.out("returned", box_inertia(3.0, Vec3(1, 2, 4)));
}
WB_PROBE("R1", "sphere", "sphere_inertia: mass 3, radius 0.5") {
  P.call("sphere_inertia"), P.in("m", 3.0), P.in("radius", 0.5);
  P.out("returned", sphere_inertia(3.0, 0.5));
}
WB_PROBE("R1", "cylinder", "cylinder_inertia: mass 3, radius 0.5, length 2 (along z)") {
  P.call("cylinder_inertia"), P.in("m", 3.0), P.in("radius", 0.5), P.in("length", 2.0);
  P.out("returned", cylinder_inertia(3.0, 0.5, 2.0));
}

}  // namespace probe_R1_body_inertia
