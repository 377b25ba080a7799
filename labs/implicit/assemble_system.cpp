#include "assemble_system.h"

#include <vector>

#include "spring_derivatives.h"

// TODO(I3) assembly of one Newton step's sparse system (see assemble_system.h).
// Plan: 1. first = sys.slot.empty(); if first, a std::vector<Eigen::Triplet<double>>,
//          else A.coeffs().setZero(); one function add(row, col, value) that makes a
//          triplet (first) or adds value at A.coeffs()[sys.slot[k++]] (later);
//       2. for each particle p, the diagonal m_p + h drag (m_p alone if pinned) at
//          rows 2p, 2p+1; b starts as M (v0 - vl) + h (f_ext - drag vl);
//       3. for each spring: spring_derivatives at (xl, vl) gives f, K, D;
//          B = -h D - h^2 K goes to the blocks (i,i), (j,j) and -B to the block
//          (min(i,j), max(i,j)): upper-triangle entries only, and skip any block
//          that touches a pinned particle;
//          b_i += h (f + K (w_i - w_j)) and b_j -= the same, with
//          w = x0 + h vl - xl (an anchor has w = 0);
//       4. b_p = 0 for pinned particles;
//       5. if first: A.resize(2n, 2n), A.setFromTriplets(...), then each triplet's
//          slot in order: &A.coeffRef(row, col) - A.valuePtr().
void assemble_system(const SpringNetwork& net, const wb::Mat2X& x0, const wb::Mat2X& v0,
                     const wb::Mat2X& xl, const wb::Mat2X& vl, const wb::Mat2X& f_ext, double h,
                     bool definite, SparseSystem& sys) {
  // ---- Replace with your code ----
  (void)x0, (void)v0, (void)xl, (void)vl, (void)f_ext, (void)h, (void)definite;
  sys.A.resize(2 * net.n(), 2 * net.n());
  sys.A.setZero();
  sys.b = Eigen::VectorXd::Zero(2 * net.n());
  // ---- end ----
}
