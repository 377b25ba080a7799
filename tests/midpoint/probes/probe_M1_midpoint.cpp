// Diagnosis probes of M1 (tests/common/wb_probe_step.h).
#include "midpoint.h"
#include "wb_probe_step.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_M1_midpoint {

WB_STEP_PROBES("M1", midpoint_step, "midpoint_step")

}  // namespace probe_M1_midpoint
