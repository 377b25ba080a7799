#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <cmath>

#include "assemble_system.h"
#include "backward_euler.h"

// Alternative I4: correct but slower, the way the lab was first written: a new
// SimplicialLDLT for every solve (in its default fill-reducing order, analysed
// each time), the workspace's LDLT unused; CG as the header asks (the step's
// first solve from ws.dv). One loop for every solve.
NewtonReport backward_euler_step(const SpringNetwork& net, const wb::Mat2X& f_ext, double h,
                                 const NewtonOptions& opt, wb::Mat2X& x, wb::Mat2X& v,
                                 NewtonWorkspace& ws) {
  NewtonReport rep;
  for (Eigen::Index p = 0; p < net.n(); ++p)
    if (net.is_pinned(p)) v.col(p).setZero();
  wb::Mat2X y = v, xl = x;
  Eigen::VectorXd dv;
  for (int k = 0;; ++k) {
    assemble_system(net, x, v, xl, y, f_ext, h, opt.definite, ws.sys);
    const Eigen::SparseMatrix<double>& A = ws.sys.A;
    const Eigen::VectorXd& b = ws.sys.b;
    if (k == 0) {
      rep.scale = (v * net.m.asDiagonal()).norm() + b.norm() + h * f_ext.norm();
    } else {
      rep.residual = b.norm();
      rep.converged = rep.residual <= opt.tol * rep.scale;
      if (rep.converged || rep.iterations >= opt.max_iterations) break;
    }
    bool ok;
    if (opt.solver == NewtonOptions::kCG) {
      Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Upper> cg(A);
      cg.setTolerance(b.norm() > 0 ? opt.cg_tol * rep.scale / b.norm() : 1.0);
      dv = k == 0 && ws.dv.size() == b.size() ? Eigen::VectorXd(cg.solveWithGuess(b, ws.dv))
                                              : Eigen::VectorXd(cg.solve(b));
      ok = cg.info() == Eigen::Success;
    } else {
      const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper> ldlt(A);
      ok = ldlt.info() == Eigen::Success;
      if (ok) dv = ldlt.solve(b);
    }
    if (!ok || !dv.allFinite()) {
      rep.solver_failed = true;
      if (k == 0) rep.residual = std::nan("");
      break;
    }
    if (k == 0) ws.dv = dv;
    y += Eigen::Map<const wb::Mat2X>(dv.data(), 2, net.n());
    ++rep.iterations;
    if (opt.one_iteration) {
      rep.residual = std::nan("");
      rep.converged = true;
      break;
    }
    xl = x + h * y;
  }
  x += h * y;
  v = y;
  return rep;
}
