// Diagnosis probes of E1 (tests/common/wb_probe_step.h).
#include "explicit_euler.h"
#include "wb_probe_step.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_E1_explicit_euler {

WB_STEP_PROBES("E1", explicit_euler_step, "explicit_euler_step", wbprobe::kState,
               wbprobe::kTellParts)

}  // namespace probe_E1_explicit_euler
