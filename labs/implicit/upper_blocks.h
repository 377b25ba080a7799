// I3's matrix A (its stored upper triangle) read 2 x 2 block by block, for
// CG's products, and CG's Jacobi preconditioner on it. Provided, not a task:
// I4 hands A to it (handouts/implicit.md#i4, backward_euler.h).
//
// Why. CG's cost is its products: on the 100 x 100 cloth about 48 a step, each
// reading all of A. Eigen's product with a SparseMatrix's upper triangle
// (selfadjointView<Upper>) reads every stored entry with its own row index and
// updates two rows per entry: 266 000 entries, 3.2 MB, about 0.18 ms a product
// on the machine of docs/benchmarks.md. The springs make A of 2 x 2 blocks,
// one per particle and one per spring, so the same product can read one
// column index per block and each x_q and y_q once per block: 2.1 MB, about
// 0.13 ms (bench_implicit, product/cloth_*). Nothing else changes: the same
// A, the same products up to rounding, the same CG.
//
// How. compute(A) analyses A's pattern (where each stored entry goes among the
// blocks) when it differs from the last one it analysed, then copies A's values
// into the blocks: a pass over A per solve that costs about two products,
// against about 48 products. Entries of the lower triangle are ignored, as
// Eigen::Upper ignores them, and any pattern works (an entry missing from a
// block reads as 0).
//
//   UpperBlocks blocks;   // kept from solve to solve (NewtonWorkspace)
//   blocks.compute(A);
//   Eigen::ConjugateGradient<UpperBlocks, Eigen::Lower | Eigen::Upper, UpperBlocksJacobi> cg;
//   cg.compute(blocks);   // then setTolerance, solveWithGuess, info() as usual
//
// In the grader, a NewtonWorkspace's blocks do not cross from the tests to your
// code (what A determines, as its ldlt): your code's start empty on every call.
// grader: not data: UpperBlocks UpperBlocksJacobi
#pragma once
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

class UpperBlocks;

namespace Eigen::internal {
// Eigen's solvers read a matrix type's traits: those of a sparse matrix of doubles.
template <>
struct traits<UpperBlocks> : public traits<Eigen::SparseMatrix<double>> {};
}  // namespace Eigen::internal

class UpperBlocks : public Eigen::EigenBase<UpperBlocks> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum {
    ColsAtCompileTime = Eigen::Dynamic,
    MaxColsAtCompileTime = Eigen::Dynamic,
    IsRowMajor = false
  };

  Eigen::Index rows() const { return 2 * n_; }
  Eigen::Index cols() const { return 2 * n_; }

  // A: 2n x 2n, symmetric, given by its upper triangle (row <= column).
  void compute(const Eigen::SparseMatrix<double>& A) {
    if (A.rows() != A.cols() || A.rows() % 2 != 0) {
      throw std::invalid_argument("UpperBlocks::compute: A must be square, of even size");
    }
    if (!A.isCompressed()) {
      Eigen::SparseMatrix<double> c = A;
      c.makeCompressed();
      compute(c);
      return;
    }
    if (!same_pattern(A)) analyse(A);
    const double* a = A.valuePtr();
    for (std::size_t e = 0; e < dest_.size(); ++e)
      if (dest_[e] >= 0) values_[std::size_t(dest_[e])] = a[e];
  }

  // y += alpha A x (x, y: 2n contiguous doubles, distinct).
  void add_product(const double* x, double* y, double alpha) const {
    const double* d = values_.data();  // the diagonal blocks: 3 a particle
    const double* o = d + 3 * n_;      // the other blocks: 4 each, row p's together
    for (Eigen::Index p = 0; p < n_; ++p) {
      const double x0 = x[2 * p], x1 = x[2 * p + 1];
      double y0 = d[3 * p] * x0 + d[3 * p + 1] * x1;
      double y1 = d[3 * p + 1] * x0 + d[3 * p + 2] * x1;
      for (int k = first_[std::size_t(p)]; k < first_[std::size_t(p) + 1]; ++k) {
        const int q = col_[std::size_t(k)];
        const double* b = o + 4 * k;  // a(2p,2q), a(2p+1,2q), a(2p,2q+1), a(2p+1,2q+1)
        const double xq0 = x[2 * q], xq1 = x[2 * q + 1];
        y0 += b[0] * xq0 + b[2] * xq1;  // block (p, q) times x_q
        y1 += b[1] * xq0 + b[3] * xq1;
        y[2 * q] += alpha * (b[0] * x0 + b[1] * x1);  // its transpose, block (q, p), times x_p
        y[2 * q + 1] += alpha * (b[2] * x0 + b[3] * x1);
      }
      y[2 * p] += alpha * y0;
      y[2 * p + 1] += alpha * y1;
    }
  }

  // A's diagonal entry (i, i).
  double diagonal(Eigen::Index i) const {
    return values_[std::size_t(3 * (i / 2) + 2 * (i % 2))];
  }

  template <class Rhs>
  Eigen::Product<UpperBlocks, Rhs, Eigen::AliasFreeProduct> operator*(
      const Eigen::MatrixBase<Rhs>& x) const {
    return Eigen::Product<UpperBlocks, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }

 private:
  bool same_pattern(const Eigen::SparseMatrix<double>& A) const {
    const std::size_t outer = std::size_t(A.outerSize()) + 1, nnz = std::size_t(A.nonZeros());
    return A.rows() == 2 * n_ && outer_.size() == outer && inner_.size() == nnz &&
           std::memcmp(outer_.data(), A.outerIndexPtr(), outer * sizeof(int)) == 0 &&
           (nnz == 0 || std::memcmp(inner_.data(), A.innerIndexPtr(), nnz * sizeof(int)) == 0);
  }

  void analyse(const Eigen::SparseMatrix<double>& A) {
    n_ = A.rows() / 2;
    outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
    inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    // The off-diagonal blocks (p, q), p < q, that hold a stored entry, row by row.
    struct Entry {
      int p, q, e, slot;
    };
    std::vector<Entry> off;
    dest_.assign(inner_.size(), -1);
    for (int c = 0; c < int(A.outerSize()); ++c) {
      for (int e = outer_[std::size_t(c)]; e < outer_[std::size_t(c) + 1]; ++e) {
        const int r = inner_[std::size_t(e)];
        if (r > c) continue;  // the lower triangle: not read
        const int p = r / 2, q = c / 2;
        if (p == q) {
          dest_[std::size_t(e)] = 3 * p + (r % 2) + (c % 2);  // (0,0), (0,1), (1,1)
        } else {
          off.push_back({p, q, e, (r % 2) + 2 * (c % 2)});
        }
      }
    }
    std::sort(off.begin(), off.end(), [](const Entry& a, const Entry& b) {
      return a.p != b.p ? a.p < b.p : a.q != b.q ? a.q < b.q : a.slot < b.slot;
    });
    first_.assign(std::size_t(n_) + 1, 0);
    col_.clear();
    for (std::size_t i = 0; i < off.size(); ++i) {
      if (i == 0 || off[i].p != off[i - 1].p || off[i].q != off[i - 1].q) {
        col_.push_back(off[i].q);
        ++first_[std::size_t(off[i].p) + 1];
      }
      const std::size_t k = col_.size() - 1;
      dest_[std::size_t(off[i].e)] = int(3 * n_ + 4 * Eigen::Index(k)) + off[i].slot;
    }
    for (std::size_t p = 0; p < std::size_t(n_); ++p) first_[p + 1] += first_[p];
    values_.assign(std::size_t(3 * n_) + 4 * col_.size(), 0.0);
  }

  Eigen::Index n_ = 0;
  std::vector<int> outer_, inner_;  // the pattern analysed (A's arrays)
  std::vector<int> dest_;           // for each stored entry of A, its place in values_, or -1
  std::vector<int> first_, col_;    // row p's blocks: first_[p] .. first_[p+1] - 1, column col_
  std::vector<double> values_;      // the diagonal blocks (3 each), then the others (4 each)
};

namespace Eigen::internal {
// y += alpha A x for Eigen's expressions (what CG's `mat * p` evaluates to).
template <typename Rhs>
struct generic_product_impl<UpperBlocks, Rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<UpperBlocks, Rhs, generic_product_impl<UpperBlocks, Rhs>> {
  template <typename Dest>
  static void scaleAndAddTo(Dest& dst, const UpperBlocks& lhs, const Rhs& rhs,
                            const double& alpha) {
    if (dst.size() != lhs.rows() || rhs.size() != lhs.cols()) {
      throw std::invalid_argument("UpperBlocks: a product with a vector of the wrong size");
    }
    const Eigen::Ref<const Eigen::VectorXd> x(rhs);  // copied only if not contiguous
    if constexpr (std::is_same_v<Dest, Eigen::VectorXd>) {
      if (x.data() != dst.data()) {
        lhs.add_product(x.data(), dst.data(), alpha);  // CG's case: no copy
        return;
      }
    }
    Eigen::VectorXd y = dst, xc = x;
    lhs.add_product(xc.data(), y.data(), alpha);
    dst = y;
  }
};
}  // namespace Eigen::internal

// CG's Jacobi preconditioner on UpperBlocks (Eigen's DiagonalPreconditioner reads
// a SparseMatrix): z = r ./ diag(A), an entry that is 0 taken as 1.
class UpperBlocksJacobi {
 public:
  UpperBlocksJacobi& analyzePattern(const UpperBlocks&) { return *this; }
  UpperBlocksJacobi& factorize(const UpperBlocks& A) {
    inv_.resize(A.rows());
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      const double d = A.diagonal(i);
      inv_[i] = d == 0.0 ? 1.0 : 1.0 / d;
    }
    return *this;
  }
  UpperBlocksJacobi& compute(const UpperBlocks& A) { return factorize(A); }
  template <typename Rhs>
  Eigen::VectorXd solve(const Eigen::MatrixBase<Rhs>& b) const {
    return inv_.cwiseProduct(b.derived());
  }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

 private:
  Eigen::VectorXd inv_;
};
