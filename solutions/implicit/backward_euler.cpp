#include "backward_euler.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <cmath>

#include "assemble_system.h"

namespace {

// Solves A dv = b with the chosen solver; false when the solver fails.
bool solve(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
           const NewtonOptions& opt, Eigen::VectorXd& dv) {
  if (opt.solver == NewtonOptions::kCG) {
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
    cg.setTolerance(opt.cg_tol);
    cg.compute(A);
    if (cg.info() != Eigen::Success) return false;
    dv = cg.solve(b);
    if (cg.info() != Eigen::Success) return false;
  } else {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
    if (ldlt.info() != Eigen::Success) return false;
    dv = ldlt.solve(b);
    if (ldlt.info() != Eigen::Success) return false;
  }
  return dv.allFinite();
}

}  // namespace

// TODO(I4) backward Euler step of a spring network by Newton's method (see backward_euler.h).
NewtonReport backward_euler_step(const SpringNetwork& net, const wb::Mat2X& f_ext, double h,
                                 const NewtonOptions& opt, wb::Mat2X& x, wb::Mat2X& v) {
  NewtonReport rep;
  const Eigen::Index n = net.n();
  // Pinned particles never move.
  for (Eigen::Index p = 0; p < n; ++p)
    if (net.is_pinned(p)) v.col(p).setZero();

  Eigen::SparseMatrix<double> A;
  Eigen::VectorXd b, dv;
  wb::Mat2X y = v;
  Eigen::Map<Eigen::VectorXd> yv(y.data(), 2 * n);

  // First solve, linearised at the start (Baraff and Witkin).
  assemble_system(net, x, v, x, v, f_ext, h, opt.definite, A, b);
  rep.scale = (v * net.m.asDiagonal()).norm() + b.norm() + h * f_ext.norm();
  if (!solve(A, b, opt, dv)) {
    rep.solver_failed = true;
  } else {
    yv += dv;
    rep.iterations = 1;
  }

  // Newton iterations on the residual G(y) = -b at (x + h y, y).
  while (!rep.solver_failed) {
    const wb::Mat2X xl = x + h * y;
    assemble_system(net, x, v, xl, y, f_ext, h, opt.definite, A, b);
    rep.residual = b.norm();
    rep.converged = rep.residual <= opt.tol * rep.scale;
    if (opt.one_iteration) {
      rep.converged = true;
      break;
    }
    if (rep.converged || rep.iterations >= opt.max_iterations) break;
    if (!solve(A, b, opt, dv)) {
      rep.solver_failed = true;
      break;
    }
    yv += dv;
    ++rep.iterations;
  }
  if (rep.solver_failed && rep.iterations == 0) rep.residual = std::nan("");

  // Advance with the last good iterate.
  x += h * y;
  v = y;
  return rep;
}
