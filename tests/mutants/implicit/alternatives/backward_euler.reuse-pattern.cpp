#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <cmath>

#include "assemble_system.h"
#include "backward_euler.h"

// Alternative I4: one loop for every solve, and the LDLT's symbolic analysis
// (the fill-reducing ordering) done once per step, since the matrix's pattern
// does not change between Newton iterations.
NewtonReport backward_euler_step(const SpringNetwork& net, const wb::Mat2X& f_ext, double h,
                                 const NewtonOptions& opt, wb::Mat2X& x, wb::Mat2X& v) {
  NewtonReport rep;
  for (Eigen::Index p = 0; p < net.n(); ++p)
    if (net.is_pinned(p)) v.col(p).setZero();
  wb::Mat2X y = v, xl = x;
  Eigen::SparseMatrix<double> A;
  Eigen::VectorXd b, dv;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
  cg.setTolerance(opt.cg_tol);
  for (int k = 0;; ++k) {
    assemble_system(net, x, v, xl, y, f_ext, h, opt.definite, A, b);
    if (k == 0) {
      rep.scale = (v * net.m.asDiagonal()).norm() + b.norm() + h * f_ext.norm();
    } else {
      rep.residual = b.norm();
      rep.converged = opt.one_iteration || rep.residual <= opt.tol * rep.scale;
      if (opt.one_iteration || rep.converged || rep.iterations >= opt.max_iterations) break;
    }
    bool ok;
    if (opt.solver == NewtonOptions::kCG) {
      cg.compute(A);
      dv = cg.solve(b);
      ok = cg.info() == Eigen::Success;
    } else {
      if (k == 0) ldlt.analyzePattern(A);
      ldlt.factorize(A);
      ok = ldlt.info() == Eigen::Success;
      if (ok) dv = ldlt.solve(b);
    }
    if (!ok || !dv.allFinite()) {
      rep.solver_failed = true;
      if (k == 0) rep.residual = std::nan("");
      break;
    }
    y += Eigen::Map<const wb::Mat2X>(dv.data(), 2, net.n());
    ++rep.iterations;
    xl = x + h * y;
  }
  x += h * y;
  v = y;
  return rep;
}
