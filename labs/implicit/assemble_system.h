// TODO(I3) assembly of one Newton step's sparse system. Handout:
// handouts/implicit.md#i3. Tests: [I3].
#pragma once
#include <Eigen/SparseCore>
#include <vector>

#include "spring_network.h"

// Backward Euler for a spring network, with the velocities y = v' at the end
// of the step as unknowns (positions follow: x' = x0 + h y):
//
//   G(y) = M (y - v0) - h ( f(x0 + h y, y) + f_ext ) = 0
//
// where f is the network's force (springs and drag) and f_ext the other
// forces, held constant. Linearising f around a point (xl, vl) and writing
// y = vl + dv gives one linear system A dv = b with
//
//   A = M - h D - h^2 K
//   b = M (v0 - vl) + h ( f(xl, vl) + f_ext ) + h K (x0 + h vl - xl)
//
// K = df/dx, D = df/dv (2n x 2n) at (xl, vl), from the springs' blocks (I2)
// and the drag (D gets -drag on its diagonal). Two uses:
//   - (xl, vl) = (x0, v0): b = h (f + f_ext + h K v0), the single linear
//     solve of Baraff and Witkin (1998);
//   - xl = x0 + h vl (a Newton iterate): the K term vanishes and b = -G(vl),
//     the residual.
//
// Unknowns are ordered particle by particle: dv = (dv_0x, dv_0y, dv_1x, ...).
// A pinned particle p does not move: its two rows and columns hold m_p on the
// diagonal and nothing else, and b_p = 0, so that dv_p = 0. (Its springs still
// act on their other ends, in f and in those ends' diagonal blocks.) The
// caller gives pinned particles vl = 0, xl = x0.
//
// A is symmetric: only its UPPER triangle (row <= column) is stored, half the
// memory and half the work of every product; Eigen's solvers read that
// triangle when told so (Eigen::Upper, as in backward_euler.h). A 2 x 2
// block (p, q) with p < q is stored whole, block (q, p) not at all (it is its
// transpose), and a diagonal block keeps its entries (0,0), (0,1), (1,1).
//
// The springs, and so A's pattern (where its entries are), never change
// during a run: only the values do. The first assembly of a system builds the
// pattern; every later one writes the values into it:
//   - first (sys.slot empty): collect Eigen::Triplet's, A.setFromTriplets
//     (it sorts them and sums duplicates), then record for each triplet, in
//     the order they were made, where its value went:
//       slot.push_back(&A.coeffRef(row, col) - A.valuePtr());
//   - later (sys.slot not empty): A.coeffs().setZero(), then make the same
//     values in the same order and add each at its slot:
//       A.coeffs()[slot[k++]] += value;
//     no triplets, no sort, no allocation: A keeps its arrays and pattern.
//     (A.coeffs()[i] is A.valuePtr()[i] with Eigen's index check: a wrong
//     slot stops with an error in a checked build, as the grader's is, instead
//     of writing past A's values.)
// So the values an assembly makes, and their order, must depend on the
// network only (its springs and pinned particles), never on the state.
struct SparseSystem {
  Eigen::SparseMatrix<double> A;  // 2n x 2n, its upper triangle
  Eigen::VectorXd b;              // 2n right-hand side (kg m/s)
  std::vector<int> slot;          // for each value an assembly adds, in order, its index in
                                  // A.valuePtr(); empty: no pattern yet
};

// Inputs:
//   net       masses, springs, drag, pinned flags (n particles)
//   x0, v0    the state at the start of the step (2 x n; m, m/s)
//   xl, vl    the linearisation point (2 x n; m, m/s)
//   f_ext     the other forces (2 x n, N)
//   h         step size (s), > 0
//   definite  passed to spring_derivatives (I2)
// Input and output:
//   sys       the system of this network: empty before the first call, then
//             kept between calls (one per network). On return: A (2n x 2n,
//             upper triangle: for each particle its diagonal block, for each
//             spring between two free particles its off-diagonal block;
//             nothing else is stored), b (2n), and slot.
void assemble_system(const SpringNetwork& net, const wb::Mat2X& x0, const wb::Mat2X& v0,
                     const wb::Mat2X& xl, const wb::Mat2X& vl, const wb::Mat2X& f_ext, double h,
                     bool definite, SparseSystem& sys);
