// Diagnosis probes of M2 (tests/midpoint/probes/midpoint_probes.h).
#include "midpoint_probes.h"
#include "trapezoid.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_M2_trapezoid {

// Details only: no probe of the trapezoid tells its parts apart. X' = (X_a + X_b) / 2, so a
// mistake in the second stage and one in the average change the same outputs in the same
// situations (the new position or velocity with a wrong weight on a(X) or a(X_a)), and an
// extra evaluation looks the same whether its result is used in the average or not: a part
// named from which outputs are wrong was wrong for 2 of the 9 catalogued mistakes with the
// generic step probes, and for every probe set tried without naming a wrong part on mistakes
// written apart from the catalogue. A failing M2 gets the counterexample of the simplest
// wrong probe.
MIDPOINT_STEP_DETAILS("M2", trapezoid_step, "trapezoid_step")

}  // namespace probe_M2_trapezoid
