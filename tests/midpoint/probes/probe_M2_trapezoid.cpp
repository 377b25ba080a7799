// Diagnosis probes of M2 (tests/midpoint/probes/midpoint_probes.h).
#include "midpoint_probes.h"
#include "trapezoid.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_M2_trapezoid {

// The step probes are details; the stages probe (midpoint_probes.h) tells the two parts
// apart: the first stage and its evaluations, the second stage and the average.
MIDPOINT_STEP_DETAILS("M2", trapezoid_step, "trapezoid_step")

// The stages (midpoint_probes.h): a(X) and a at the second state free of each other.
WB_PROBE("M2", "stages",
         "three moving particles, a = A_i at the start state and G_i at any other, h = 0.25: x, "
         "v and the evaluations") {
  wbprobe::stages(P, &trapezoid_step, "trapezoid_step", true);
}

}  // namespace probe_M2_trapezoid
