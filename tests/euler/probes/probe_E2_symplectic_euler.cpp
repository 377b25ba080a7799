// Diagnosis probes of E2 (tests/common/wb_probe_step.h).
#include "symplectic_euler.h"
#include "wb_probe_step.h"

WB_STEP_PROBES("E2", symplectic_euler_step, "symplectic_euler_step")
