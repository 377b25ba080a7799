// Diagnosis probes of E2 (tests/common/wb_probe_step.h).
#include "symplectic_euler.h"
#include "wb_probe_step.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_E2_symplectic_euler {

WB_STEP_PROBES("E2", symplectic_euler_step, "symplectic_euler_step",
               wbprobe::kState | wbprobe::kEach, wbprobe::kTellParts)

}  // namespace probe_E2_symplectic_euler
