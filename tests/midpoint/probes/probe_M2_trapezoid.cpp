// Diagnosis probes of M2 (tests/common/wb_probe_step.h).
#include "trapezoid.h"
#include "wb_probe_step.h"

WB_STEP_PROBES("M2", trapezoid_step, "trapezoid_step")
