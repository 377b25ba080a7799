// Diagnosis probes of C3 (tests/common/wb_probe.h): the pairs found, sorted (ascending), and
// those written the wrong way round, of: a pair across a cell narrower than a diameter,
// neighbours across a cell's side and across its corner, discs that just touch, one large disc
// among small ones, a list that comes in holding old pairs.
#include <algorithm>

#include "grid_pairs.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_C3_grid_pairs {

using wbprobe::cols;
using wbprobe::vec;

namespace {
void run(wbprobe::Probe& P, const wb::Mat2X& x, const wb::VecX& radius,
         std::vector<std::pair<int, int>> pairs) {
  P.call("grid_pairs");
  P.in("x", x), P.in("radius", radius);
  if (!pairs.empty()) P.in("pairs", pairs);
  grid_pairs(x, radius, pairs);
  // Which pairs were found apart from how each is written: the set (each pair as (min, max),
  // in order: any order is right), then the pairs written (j, i) with j > i (the header's is
  // (i, j), i < j), so that a pair the other way round does not read as one missed and another
  // found (a mistake of the grid).
  std::vector<std::pair<int, int>> found, reversed;
  for (const auto& [i, j] : pairs) {
    found.emplace_back(std::min(i, j), std::max(i, j));
    if (i > j) reversed.emplace_back(i, j);
  }
  std::sort(found.begin(), found.end());
  std::sort(reversed.begin(), reversed.end());
  P.out("pairs", found);
  P.out("pairs written (j, i), j > i", reversed);
}
}  // namespace

WB_PROBE("C3", "two", "two overlapping discs of radius 0.5") {
  P.simple();
  run(P, cols({{0, 0}, {0.8, 0}}), vec({0.5, 0.5}), {});
}
// A pair 0.95 apart along x, overlapping (radius 0.5): in neighbouring cells of any grid whose
// cells are at least a diameter wide, two cells apart in one whose cells are narrower (the
// radius, 1.5 radii), whether the cells are counted from the smallest coordinates (the discs at
// the origin and above it) or from the origin.
WB_PROBE("C3", "straddle",
         "discs of radius 0.5 at the origin, (0.6, 0), (1.55, 0) and (0, 1.5): two of them 0.95 "
         "apart, across a cell narrower than a diameter") {
  P.simple();
  run(P, cols({{0, 0}, {0.6, 0}, {1.55, 0}, {0, 1.5}}), vec({0.5, 0.5, 0.5, 0.5}), {});
}
// Pairs in neighbouring cells, along the sides and across the corners (both diagonals).
WB_PROBE("C3", "cluster",
         "nine discs of radius 0.3 on a 0.55 lattice: every neighbour, diagonals included") {
  wb::Mat2X x(2, 9);
  for (int i = 0; i < 9; ++i) x.col(i) = wb::Vec2(0.55 * (i % 3), 0.55 * (i / 3));
  run(P, x, wb::VecX::Constant(9, 0.3), {});
}
// Four discs around the point (1, 1), one in each of the unit cells that meet there (cells as
// wide as the largest diameter, counted from the smallest coordinates or from the origin: the
// disc at the origin makes both the same), so close that any grid with cells at least as wide
// as a diameter finds them in neighbouring cells: only a missing neighbour (across a side, or
// either diagonal) loses a pair here.
WB_PROBE("C3", "diagonal",
         "discs of radius 0.5 at (0.9, 0.9), (1.1, 0.9), (0.9, 1.1), (1.1, 1.1) and the origin: "
         "pairs across both diagonals of a corner") {
  run(P, cols({{0, 0}, {0.9, 0.9}, {1.1, 0.9}, {0.9, 1.1}, {1.1, 1.1}}),
      vec({0.5, 0.5, 0.5, 0.5, 0.5}), {});
}
// Touching exactly (|dx| = r_i + r_j) counts.
WB_PROBE("C3", "touching", "discs of radius 0.25 exactly 0.5 apart along x and along y") {
  run(P, cols({{0, 0}, {0.5, 0}, {0, 0.5}, {3, 3}}), vec({0.25, 0.25, 0.25, 0.25}), {});
}
// One large disc among small ones.
WB_PROBE("C3", "large", "one disc of radius 1.5 among discs of radius 0.1") {
  run(P, cols({{0, 0}, {1.45, 0.3}, {-1.2, 0.7}, {0.3, -1.5}, {3.5, 0}, {3.6, 0.1}}),
      vec({1.5, 0.1, 0.1, 0.1, 0.1, 0.1}), {});
}
// A list that holds old pairs.
WB_PROBE("C3", "stale",
         "two overlapping discs, the list coming in with old pairs (0, 5) and (2, 3)") {
  run(P, cols({{0, 0}, {0.8, 0}, {3, 3}}), vec({0.5, 0.5, 0.5}), {{0, 5}, {2, 3}});
}

}  // namespace probe_C3_grid_pairs
