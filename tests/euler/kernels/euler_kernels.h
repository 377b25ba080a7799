// The loops of the euler tests' long runs (10^6 steps), as one function each: in the grader's
// build a test's calls to the lab go to a separate worker process, and a call per step would
// cost a million round trips; this function runs beside the lab's code, so it is one call
// (docs/grading.md "Batching"). In an ordinary build it is a plain function.
#pragma once
#include "wb/types.h"

// n steps of the explicit (method 0) or semi-implicit (method 1) Euler step on the harmonic
// oscillator a = -w^2 x (unit masses), the work arrays NaN on entry to every step, as the
// tests' Run does. After step k (0-based) with k % sample == 0, the energy
// E = 1/2 |v|^2 + 1/2 w^2 |x|^2 is sampled into [e_min, e_max] (which start as the caller's).
void euler_oscillator_run(int method, double w, double h, long n, long sample, wb::Mat2X& x,
                          wb::Mat2X& v, double& e_min, double& e_max);
