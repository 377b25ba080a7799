// The provided fast path of backward Euler on a spring network: the same step
// as the lab's backward_euler_step (I3, I4), with the same spring derivatives
// (the lab's spring_derivatives, I2), organised the way an engine does it.
// Not a student task; handouts/implicit.md, "What it costs", says what differs
// from the teaching version and why; docs/benchmarks.md, ## implicit, measures
// both.
//
// What is done once per run instead of once per solve:
//   - the pattern of A = M - h D - h^2 K (the springs never change): built once
//     in compressed (CSC) form, with the position of each spring's 2 x 2
//     blocks in the value array. Assembling a step writes the values in place:
//     no triplets, no sort, no allocation;
//   - a direct solver's analysis of that pattern (fill-reducing ordering,
//     elimination tree, the factor's structure); each solve refactorises
//     numerically only;
//   - the choice of solver: the analysis counts the factorisation's flops.
//     A rope's factor has no fill (a few flops per unknown): direct. A 2D
//     cloth's fills in (~n^1.5 flops): preconditioned conjugate gradients,
//     whose work per solve grows like n.
#pragma once
#include <memory>
#include <string>

#include "backward_euler.h"
#include "spring_network.h"
#include "wb/cost.h"

namespace wb {

struct FastSolverOptions {
  // auto: direct when a factorisation costs at most kDirectBudget CG iterations
  // (fast_backward_euler.cpp), else cg. ldlt: Eigen::SimplicialLDLT; cholmod:
  // SuiteSparse's supernodal Cholesky (falls back to ldlt when the build has no
  // CHOLMOD, or when A is not positive definite); cg: conjugate gradients with a
  // block-Jacobi preconditioner (each particle's 2 x 2 diagonal block of A),
  // warm-started from the previous step's dv, on A stored spring by spring.
  enum Solver { kAuto, kLDLT, kCholmod, kCG };
  Solver solver = kAuto;
  // CG stops when |A dv - b| <= cg_tol * (|M v| + |b_0| + h |f_ext|): the
  // momenta the step moves, the scale of the lab's Newton test. One solve's
  // own linearisation error is larger than that (on the 10^4 cloth the energy
  // after 1 s moves by 0.15 J between 1e-3 and 1e-2, where the step removes
  // 44 J), so a tighter solve buys nothing. In Newton's later iterations, CG
  // also stops at 1e-3 of the current residual |b| (inexact Newton).
  double cg_tol = 1e-2;
  // The cost model's running checks (docs/scenes.md, "Cost"), counted as the work
  // is done: CG iterations and Newton's linear solves. Null: not counted. Each
  // step starts a new step of both.
  WorkMeter* cg_meter = nullptr;
  WorkMeter* newton_meter = nullptr;
};

// One LDLT factorisation of the network's system in the unknowns' own order (the lab's
// NewtonWorkspace::ldlt), in CG iterations: the count the fast path's auto makes, from the
// elimination tree of the free particles' graph, without factorising. The walk stops
// once the ratio passes `cap` (a pattern that fills in is known to be dear in O(n)), so
// the answer is exact up to `cap` and only "more than cap" beyond.
double natural_order_factor_ratio(const SpringNetwork& net, double cap);
// The budget auto uses: a direct solve when one factorisation costs at most this many
// CG iterations.
double direct_budget_iterations();

// True when this build has SuiteSparse's CHOLMOD (CMake option WB_CHOLMOD).
bool have_cholmod();

class FastBackwardEuler {
 public:
  // Analyses the network's pattern (once per run). The network must outlive
  // this object and keep its springs and pins.
  FastBackwardEuler(const SpringNetwork& net, const FastSolverOptions& fo);
  ~FastBackwardEuler();
  FastBackwardEuler(const FastBackwardEuler&) = delete;
  FastBackwardEuler& operator=(const FastBackwardEuler&) = delete;

  // One backward Euler step, as backward_euler_step (backward_euler.h) with
  // the same options and report. With opt.one_iteration the step does not
  // assemble again to measure its residual: report.residual is NaN.
  NewtonReport step(const Mat2X& f_ext, double h, const NewtonOptions& opt, Mat2X& x, Mat2X& v);

  // The solver in use ("ldlt", "cholmod" or "cg") and why it was chosen.
  const std::string& solver() const;
  const std::string& reason() const;
  long cg_iterations() const;  // CG iterations over the run
  long factorisations() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wb
