// The semi-implicit (symplectic) Euler step, provided to the labs whose topic
// is not integration (forces, collisions): v += h a(x, v), then x += h v with
// the new v. The euler lab's E2 is the same step written by the student.
#pragma once
#include "wb/dynamics.h"

namespace wb {

// One step of size h (a wb::StepFn): one force evaluation; uses s.a0.
void semi_implicit_euler_step(const Dynamics& dyn, double h, Mat2X& x, Mat2X& v, Scratch& s);

// The entry for a lab's integrator list: "symplectic-euler", order 1.
Integrator semi_implicit_euler_integrator();

}  // namespace wb
