// The implicit lab's provided UpperBlocks (labs/implicit/upper_blocks.h): I4's CG reads
// I3's matrix A through it, block by block. Its products must be Eigen's products with
// A's upper triangle (A.selfadjointView<Eigen::Upper>()), for any pattern a student's A
// may have, and CG on it must be Eigen's CG on A with its Jacobi preconditioner.
#include "upper_blocks.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdint>
#include <vector>

namespace {

struct Rand {  // splitmix64: uniform doubles in [0, 1) and integers in [0, k)
  std::uint64_t s;
  std::uint64_t bits() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double next() { return double(bits() >> 11) * 0x1.0p-53; }
  int below(int k) { return int(bits() % std::uint64_t(k)); }
};

// A 2n x 2n matrix of random entries at random places: both triangles (the lower one
// must be ignored), blocks partly filled, off-diagonal blocks not symmetric.
Eigen::SparseMatrix<double> random_matrix(Rand& r, int n) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < 2 * n; ++i)
    if (r.below(4) != 0) t.emplace_back(i, i, 1 + r.next());
  const int m = r.below(6 * n * n + 1);
  for (int k = 0; k < m; ++k) t.emplace_back(r.below(2 * n), r.below(2 * n), 2 * r.next() - 1);
  Eigen::SparseMatrix<double> A(2 * n, 2 * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// Rounding bound of a product's entry: each order of summing its k products errs by at most
// (k - 1) eps sum |a| |x|, so two orders differ by at most 2 (k - 1) eps sum |a| |x|; a row
// here has at most 2n <= 80 entries: 160 eps. A wrong block is off by O(1) of sum |a| |x|.
void check_same_product(const Eigen::SparseMatrix<double>& A, const UpperBlocks& B,
                        const Eigen::VectorXd& x) {
  const Eigen::VectorXd want = A.selfadjointView<Eigen::Upper>() * x;
  const Eigen::SparseMatrix<double> absA = A.cwiseAbs();
  const Eigen::VectorXd scale = absA.selfadjointView<Eigen::Upper>() * x.cwiseAbs();
  Eigen::VectorXd got = B * x;
  REQUIRE(got.size() == want.size());
  for (Eigen::Index i = 0; i < want.size(); ++i) {
    INFO("row " << i << " of " << want.size());
    CHECK(std::abs(got[i] - want[i]) <= 160 * 2.2e-16 * scale[i]);
  }
  // y += alpha A x: what Eigen's expressions make of it.
  Eigen::VectorXd y = Eigen::VectorXd::Constant(x.size(), 0.5);
  y.noalias() += 3.0 * (B * x);
  CHECK((y - (Eigen::VectorXd::Constant(x.size(), 0.5) + 3.0 * want)).cwiseAbs().maxCoeff() <=
        4 * 160 * 2.2e-16 * (1 + 3 * scale.maxCoeff()));
}

}  // namespace

TEST_CASE("UpperBlocks: its product is Eigen's with the upper triangle, any pattern",
          "[physics][implicit]") {
  Rand r{11};
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + r.below(40);
    Eigen::SparseMatrix<double> A = random_matrix(r, n);
    if (trial % 3 == 0) A.prune([](Eigen::Index i, Eigen::Index j, double) { return i <= j; });
    if (trial % 5 == 0) A.uncompress();  // a matrix left uncompressed is read as well
    INFO("trial " << trial << ", n = " << n << ", " << A.nonZeros() << " stored entries");
    UpperBlocks B;
    B.compute(A);
    Eigen::VectorXd x(2 * n);
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = 2 * r.next() - 1;
    check_same_product(A, B, x);
    // New values on the same pattern, then another pattern: each product is the new A's.
    A.coeffs() *= -2.0;
    B.compute(A);
    check_same_product(A, B, x);
    const Eigen::SparseMatrix<double> A2 = random_matrix(r, n);
    B.compute(A2);
    check_same_product(A2, B, x);
  }
}

TEST_CASE("UpperBlocks: CG on it is Eigen's CG on the stored triangle", "[physics][implicit]") {
  Rand r{12};
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 1 + r.below(40);
    // Symmetric positive definite: C^T C + I from a random C, its upper triangle stored.
    const Eigen::SparseMatrix<double> C = random_matrix(r, n);
    Eigen::SparseMatrix<double> I(2 * n, 2 * n);
    I.setIdentity();
    const Eigen::SparseMatrix<double> S = Eigen::SparseMatrix<double>(C.transpose() * C) + I;
    const Eigen::SparseMatrix<double> A = S.triangularView<Eigen::Upper>();
    Eigen::VectorXd b(2 * n);
    for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = 2 * r.next() - 1;
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Upper> eigen_cg;
    eigen_cg.setTolerance(1e-12);
    eigen_cg.compute(A);
    const Eigen::VectorXd want = eigen_cg.solve(b);
    UpperBlocks B;
    B.compute(A);
    Eigen::ConjugateGradient<UpperBlocks, Eigen::Lower | Eigen::Upper, UpperBlocksJacobi> cg;
    cg.setTolerance(1e-12);
    cg.compute(B);
    REQUIRE(cg.info() == Eigen::Success);
    const Eigen::VectorXd got = cg.solve(b);
    INFO("trial " << trial << ", n = " << n);
    REQUIRE(cg.info() == Eigen::Success);
    // Both stop at |A x - b| <= 1e-12 |b|: each is within cond(A) 1e-12 of the solution;
    // the residual is what both guarantee.
    CHECK((S * got - b).norm() <= 1e-12 * b.norm() * 1.0001);
    CHECK((S * want - b).norm() <= 1e-12 * b.norm() * 1.0001);
    // The same preconditioner, so the iterations go the same way, up to rounding in
    // another order (which moves an ill-conditioned case by an iteration or two).
    CHECK(std::abs(long(cg.iterations()) - long(eigen_cg.iterations())) <=
          std::max(2L, long(eigen_cg.iterations()) / 10));
    // Jacobi's, as Eigen's DiagonalPreconditioner: r .* (1 ./ diag(A)), a 0 read as 1.
    UpperBlocksJacobi P;
    P.compute(B);
    const Eigen::VectorXd z = P.solve(b);
    for (Eigen::Index i = 0; i < b.size(); ++i) CHECK(z[i] == b[i] * (1.0 / S.coeff(i, i)));
  }
  // A diagonal entry that is 0, or not stored, is read as 1.
  Eigen::SparseMatrix<double> D(4, 4);
  D.insert(0, 0) = 2.0;
  D.insert(1, 1) = 0.0;
  D.insert(0, 3) = 5.0;
  UpperBlocks B;
  B.compute(D);
  UpperBlocksJacobi P;
  P.compute(B);
  const Eigen::VectorXd z = P.solve(Eigen::Vector4d(1, 2, 3, 4));
  CHECK(z[0] == 0.5);
  CHECK(z[1] == 2.0);
  CHECK(z[2] == 3.0);
  CHECK(z[3] == 4.0);
}

TEST_CASE("UpperBlocks: a matrix or a vector of the wrong shape is refused",
          "[physics][implicit]") {
  UpperBlocks B;
  Eigen::SparseMatrix<double> odd(3, 3), wide(4, 6);
  CHECK_THROWS_AS(B.compute(odd), std::invalid_argument);
  CHECK_THROWS_AS(B.compute(wide), std::invalid_argument);
  Eigen::SparseMatrix<double> A(4, 4);
  A.setIdentity();
  B.compute(A);
  const Eigen::VectorXd x = Eigen::VectorXd::Ones(6);
  Eigen::VectorXd y;
  CHECK_THROWS_AS(y = B * x, std::invalid_argument);
}
