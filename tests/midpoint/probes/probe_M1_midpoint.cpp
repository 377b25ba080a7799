// Diagnosis probes of M1 (tests/midpoint/probes/midpoint_probes.h, tests/common/wb_probe_step.h).
#include "midpoint.h"
#include "midpoint_probes.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_M1_midpoint {

MIDPOINT_STEP_DETAILS("M1", midpoint_step, "midpoint_step")

// The part probe: three particles thrown from the centre of a spring (a = -4 x, zero at the
// start), with different velocities. The start acceleration is zero, so the midpoint velocity
// is v and the new position x + h v; what the midpoint position does shows in the new velocity
// and the second evaluation, the final update in the new state alone, an evaluation too many
// or too few in the evaluations alone. The scratch holds zeros (a stale start acceleration is
// then the right one here and shows only as a missing evaluation; the details hold NaN).
WB_PROBE("M1", "launch",
         "three particles thrown from the centre of a spring, a = -4 x, h = 0.25: x, v and "
         "the evaluations") {
  wbprobe::step(P, &midpoint_step, "midpoint_step", "-4 x", wbprobe::spring(4),
                wbprobe::cols({{0, 0}, {0, 0}, {0, 0}}),
                wbprobe::cols({{3, -1}, {0.5, 2}, {-1.5, -0.5}}), 0.25, wbprobe::kBoth, 0.0);
}

// The stages (midpoint_probes.h): a(X) and a at the second state free of each other.
WB_PROBE("M1", "stages",
         "three moving particles, a = A_i at the start state and G_i at any other, h = 0.25: x, "
         "v and the evaluations") {
  wbprobe::stages(P, &midpoint_step, "midpoint_step", false);
}

// The new velocity alone under the stages' forces (midpoint_probes.h): the forces asked at the
// start state twice (a second evaluation at X, not at X_mid) show here, a midpoint state built
// wrongly does not, where the launch shows both alike.
WB_PROBE("M1", "stages-v",
         "three moving particles, a = A_i at the start state and G_i at any other, h = 0.25: "
         "the new v alone") {
  wbprobe::stages_velocity(P, &midpoint_step, "midpoint_step");
}

}  // namespace probe_M1_midpoint
