#include "assemble_system.h"

#include <vector>

#include "spring_derivatives.h"

// TODO(I3) assembly of one Newton step's sparse system (see assemble_system.h).
void assemble_system(const SpringNetwork& net, const wb::Mat2X& x0, const wb::Mat2X& v0,
                     const wb::Mat2X& xl, const wb::Mat2X& vl, const wb::Mat2X& f_ext, double h,
                     bool definite, Eigen::SparseMatrix<double>& A, Eigen::VectorXd& b) {
  const Eigen::Index n = net.n();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(std::size_t(4 * n + 16 * net.springs.size()));
  // Adds the 2 x 2 block B at particles (p, q), if neither is pinned.
  auto block = [&](Eigen::Index p, Eigen::Index q, const wb::Mat2& B) {
    if (net.is_pinned(p) || net.is_pinned(q)) return;
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) t.emplace_back(2 * p + r, 2 * q + c, B(r, c));
  };

  // Mass, drag, and the parts of the right-hand side that need no spring.
  const wb::Mat2X w = x0 + h * vl - xl;  // where the positions are, minus where K was taken
  wb::Mat2X rhs = (v0 - vl) * net.m.asDiagonal();
  rhs += h * (f_ext - net.drag * vl);
  for (Eigen::Index p = 0; p < n; ++p) {
    const double diag = net.is_pinned(p) ? net.m[p] : net.m[p] + h * net.drag;
    t.emplace_back(2 * p, 2 * p, diag);
    t.emplace_back(2 * p + 1, 2 * p + 1, diag);
  }

  // Springs: force and the blocks of -h D - h^2 K.
  wb::Vec2 f;
  wb::Mat2 K, D;
  for (const NetworkSpring& s : net.springs) {
    const bool anchored = s.j < 0;
    const wb::Vec2 xj = anchored ? s.anchor : wb::Vec2(xl.col(s.j));
    const wb::Vec2 vj = anchored ? wb::Vec2::Zero() : wb::Vec2(vl.col(s.j));
    spring_derivatives(xl.col(s.i), xj, vl.col(s.i), vj, s.k, s.rest, s.kd, definite, f, K, D);
    const wb::Mat2 B = -h * D - h * h * K;
    const wb::Vec2 dw = anchored ? wb::Vec2(w.col(s.i)) : wb::Vec2(w.col(s.i) - w.col(s.j));
    const wb::Vec2 fi = f + K * dw;  // force, plus the correction of the K term
    rhs.col(s.i) += h * fi;
    block(s.i, s.i, B);
    if (!anchored) {
      rhs.col(s.j) -= h * fi;
      block(s.j, s.j, B);
      block(s.i, s.j, -B);
      block(s.j, s.i, -B);
    }
  }

  // Pinned particles: dv = 0.
  for (Eigen::Index p = 0; p < n; ++p)
    if (net.is_pinned(p)) rhs.col(p).setZero();

  A.resize(2 * n, 2 * n);
  A.setFromTriplets(t.begin(), t.end());
  b = Eigen::Map<const Eigen::VectorXd>(rhs.data(), 2 * n);
}
