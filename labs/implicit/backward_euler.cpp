#include "backward_euler.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <cmath>

#include "assemble_system.h"

// TODO(I4) backward Euler step of a spring network by Newton's method (see backward_euler.h).
// Plan: 1. set v = 0 for pinned particles; y = v (a 2 x n matrix; Eigen::Map
//          views it as the 2n vector of the unknowns);
//       2. assemble_system at (x, v) -> A, b_0; scale = |M v| + |b_0| + h |f_ext|;
//          solve A dv = b_0 with Eigen::SimplicialLDLT or
//          Eigen::ConjugateGradient<..., Eigen::Lower | Eigen::Upper> (opt.solver,
//          cg.setTolerance(opt.cg_tol)); check info() and dv.allFinite(); y += dv;
//       3. loop: assemble_system at (x + h y, y) -> A, b; residual = |b|;
//          stop if one_iteration, converged (residual <= tol scale) or
//          iterations == max_iterations; otherwise solve and y += dv;
//       4. x += h y; v = y; return the report.
NewtonReport backward_euler_step(const SpringNetwork& net, const wb::Mat2X& f_ext, double h,
                                 const NewtonOptions& opt, wb::Mat2X& x, wb::Mat2X& v) {
  // ---- Replace with your code ----
  (void)net, (void)f_ext, (void)h, (void)opt, (void)x, (void)v;
  return NewtonReport{};
  // ---- end ----
}
