// TODO(I4) backward Euler step of a spring network by Newton's method.
// Handout: handouts/implicit.md#i4. Tests: [I4].
#pragma once
#include <Eigen/SparseCholesky>

#include "assemble_system.h"
#include "spring_network.h"
#include "upper_blocks.h"

struct NewtonOptions {
  // Your step uses the solver it is given. A run chooses it: the scene's newton.solver
  // ("ldlt", "cg"), or, when the scene does not say ("auto", the default), the solver the
  // system's pattern needs: LDLT when one factorisation in the unknowns' own order costs
  // at most 30 CG iterations (counted on the pattern, without factorising: a rope, a
  // small cloth), else CG (a large cloth, whose factor fills its band; CG needs
  // `definite`, as below). The glue decides it once per run
  // (framework/drivers/implicit/implicit_world.cpp), as the provided path's auto does.
  enum Solver { kLDLT, kCG };
  Solver solver = kLDLT;       // Eigen::SimplicialLDLT, or Eigen::ConjugateGradient
  double tol = 1e-9;           // converged when |G(y)| <= tol * scale
  int max_iterations = 20;     // cap on the linear solves
  bool one_iteration = false;  // Baraff and Witkin (1998): one linear solve, no test
  bool definite = true;        // clamp compressed springs' blocks (see spring_derivatives.h)
  double cg_tol = 1e-12;       // CG stops when |A dv - b| <= cg_tol * scale (below); with
                               // Newton, keep it below tol (a correction solved less well
                               // than the residual it corrects gains nothing)
};

// What backward_euler_step did (every field is checked by the tests [I4]):
struct NewtonReport {
  int iterations = 0;          // linear solves that succeeded
  double residual = 0;         // |G(y)| at the returned y (kg m/s), Euclidean norm over the
                               // free particles; NaN when no solve succeeded
  double scale = 0;            // the momentum scale of the convergence test: step 3 below
  bool converged = false;      // residual <= tol * scale (one_iteration: the solve succeeded)
  bool solver_failed = false;  // a factorisation or CG failed, or dv was not finite
};

// What the steps of one network keep from one step to the next (the springs,
// and so the system's pattern, never change during a run): make one, empty,
// before a run's first step, and pass it to every step of that network.
struct NewtonWorkspace {
  // I3's system: its pattern and slots, from the first assembly.
  SparseSystem sys;
  // The LDLT solver, on the stored upper triangle, in the unknowns' own order
  // (NaturalOrdering): a rope numbered bead by bead is banded, and its factor
  // has no fill in that order, so there is nothing to reorder and the
  // factorisation reads A in place. (A 2D cloth's factor fills its band, about
  // n times the row length: use CG there.) Its analysis of A's pattern (the
  // structure of the factor) is done once, when ldlt.rows() differs from A's
  // (an empty workspace): ldlt.analyzePattern(A); every solve then only
  // refactorises: ldlt.factorize(A), ldlt.solve(b). Not data: a graded call
  // starts with a fresh one (it does not cross the grader's process
  // boundary), which the rows() test sees.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>>
      ldlt;
  // CG: A read 2 x 2 block by block for its products (upper_blocks.h: the
  // pattern analysed once, the values copied per solve), and the first dv of
  // the last step, the first guess of the next step's first solve (a warm
  // start: the motion is smooth, so it is already close).
  UpperBlocks blocks;
  Eigen::VectorXd dv;
};

// One backward Euler step of a spring network:
//
//   x' = x + h v',   M v' = M v + h ( f(x', v') + f_ext )
//
// solved for y = v' by Newton's method on G(y) = M (y - v) - h (f(x + h y, y) + f_ext):
//
//   1. pinned particles: v = 0 (they never move);
//   2. y = v; the first system is linearised at (x, v) (assemble_system, I3,
//      into ws.sys): A dv = b_0, y += dv;
//   3. one_iteration (Baraff and Witkin): stop, with the residual |G(y)|
//      computed from the forces (network_forces.h: no matrix needed).
//      Otherwise repeat: assemble at (x + h y, y), whose b is -G(y); stop when
//      |b| <= tol * scale (converged), or after max_iterations solves; else
//      solve A dv = b, y += dv. The scale (NewtonReport::scale) is
//
//        scale = |M v| + |b_0| + h |f_ext|      (kg m/s, Euclidean norms)
//
//      with v the start velocities of step 1 (pinned ones 0), b_0 the first
//      right-hand side and f_ext every particle's external force: the momenta
//      at stake (the residual cannot be rounded below ~1e-16 of them). Each
//      term matters: a network gliding with its springs at rest has only
//      |M v|, one released from rest without gravity only |b_0|, one at rest
//      in equilibrium under gravity only h |f_ext|;
//   4. x += h y, v = y, and report iterations and the final residual |G(y)|.
//
// The solves, with opt.solver:
//   kLDLT  ws.ldlt, analysed once (see NewtonWorkspace), factorised per solve;
//   kCG    conjugate gradients with Jacobi's preconditioner, stopped when
//          |A dv - b| <= cg_tol * scale. CG's cost is its products with A, tens
//          a step: read A block by block (upper_blocks.h), ws.blocks.compute(A),
//          then Eigen::ConjugateGradient<UpperBlocks, Eigen::Lower | Eigen::Upper,
//          UpperBlocksJacobi> on ws.blocks. (The same products, up to rounding,
//          as Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Upper>
//          on A itself, which is as right and 1.4 times slower on a cloth.)
//          Eigen's tolerance is relative to |b|, so setTolerance(cg_tol * scale / |b|).
//          The step's first solve starts from ws.dv (when it has 2n entries,
//          else from 0: solveWithGuess) and leaves its dv there; Newton's later
//          solves, which only correct, start from 0.
// A failed solve (Eigen's info() != Success, or a non-finite dv) stops the
// iteration with solver_failed and converged false, and step 4 still runs
// with the last good iterate y (y = v when the first solve failed): x and v
// are never NaN.
//
// Inputs:
//   net    the springs, masses, drag and pinned particles (n particles)
//   f_ext  the other forces (2 x n, N), taken at the start of the step
//   h      step size (s), > 0
//   opt    solver choice, tolerance, iteration cap
// Outputs:
//   x, v   2 x n positions (m) and velocities (m/s): advanced in place
//   ws     this network's workspace, updated (see NewtonWorkspace)
//   returns what Newton's method did
NewtonReport backward_euler_step(const SpringNetwork& net, const wb::Mat2X& f_ext, double h,
                                 const NewtonOptions& opt, wb::Mat2X& x, wb::Mat2X& v,
                                 NewtonWorkspace& ws);
