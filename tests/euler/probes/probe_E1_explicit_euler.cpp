// Diagnosis probes of E1 (tests/common/wb_probe_step.h).
#include "explicit_euler.h"
#include "wb_probe_step.h"

WB_STEP_PROBES("E1", explicit_euler_step, "explicit_euler_step")
