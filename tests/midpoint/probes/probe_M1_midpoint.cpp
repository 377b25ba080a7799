// Diagnosis probes of M1 (tests/common/wb_probe_step.h).
#include "midpoint.h"
#include "wb_probe_step.h"

WB_STEP_PROBES("M1", midpoint_step, "midpoint_step")
