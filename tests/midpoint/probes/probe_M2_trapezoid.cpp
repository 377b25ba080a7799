// Diagnosis probes of M2 (tests/common/wb_probe_step.h).
#include "trapezoid.h"
#include "wb_probe_step.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_M2_trapezoid {

WB_STEP_PROBES("M2", trapezoid_step, "trapezoid_step")

}  // namespace probe_M2_trapezoid
