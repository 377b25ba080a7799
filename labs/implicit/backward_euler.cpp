#include "backward_euler.h"

#include <Eigen/IterativeLinearSolvers>
#include <cmath>

#include "network_forces.h"

// TODO(I4) backward Euler step of a spring network by Newton's method (see backward_euler.h).
// Plan: 1. set v = 0 for pinned particles; y = v (a 2 x n matrix; Eigen::Map
//          views it as the 2n vector of the unknowns);
//       2. assemble_system at (x, v) into ws.sys -> A, b_0; scale = |M v| + |b_0| + h |f_ext|;
//          solve A dv = b_0: LDLT: ws.ldlt.analyzePattern(A) if ws.ldlt.rows() != A.rows(),
//          then ws.ldlt.factorize(A), ws.ldlt.solve(b); CG: ws.blocks.compute(A),
//          Eigen::ConjugateGradient<UpperBlocks, Eigen::Lower | Eigen::Upper,
//          UpperBlocksJacobi> cg, tolerance opt.cg_tol * scale / |b|, cg.compute(ws.blocks),
//          cg.solveWithGuess(b, ws.dv) (ws.dv resized to 2n zeros first if it is not 2n
//          long); check info() and
//          dv.allFinite(); y += dv, ws.dv = dv;
//       3. one_iteration: residual = |G(y)| from network_forces at (x + h y, y), stop;
//          else loop: assemble_system at (x + h y, y) -> A, b; residual = |b|;
//          stop if converged (residual <= tol scale) or iterations == max_iterations;
//          otherwise solve (CG from 0) and y += dv;
//       4. x += h y; v = y; return the report.
NewtonReport backward_euler_step(const SpringNetwork& net, const wb::Mat2X& f_ext, double h,
                                 const NewtonOptions& opt, wb::Mat2X& x, wb::Mat2X& v,
                                 NewtonWorkspace& ws) {
  // ---- Replace with your code ----
  (void)net, (void)f_ext, (void)h, (void)opt, (void)x, (void)v, (void)ws;
  return NewtonReport{};
  // ---- end ----
}
