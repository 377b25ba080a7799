#include "grid_pairs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

// A dense grid over the particles' bounding box, filled by counting sort:
//   cell_start[c] .. cell_start[c + 1] are the particles of cell c in `order`.
// Cells are at least as wide as the largest diameter, and widened when the box
// would need more cells than about 2 n (an outlier far away then costs
// nothing but a coarser grid; wider cells never lose a pair).
void grid_pairs(const wb::Mat2X& x, const wb::VecX& radius,
                std::vector<std::pair<int, int>>& pairs) {
  pairs.clear();
  const int n = int(x.cols());
  if (n < 2) return;
  const wb::Vec2 lo = x.rowwise().minCoeff(), hi = x.rowwise().maxCoeff();
  const wb::Vec2 span = hi - lo;
  // Cell size: the largest diameter with a margin for rounding in (x - lo) / size.
  double size = 2 * radius.maxCoeff() * (1 + 1e-9);
  // At most about n cells across the box, whatever its shape.
  const double area_cell = std::sqrt(span.x() * span.y() / n);
  size = std::max({size, area_cell, (span.x() + span.y()) / n, 1e-300});
  std::int64_t nx = std::int64_t(span.x() / size) + 1, ny = std::int64_t(span.y() / size) + 1;
  while (nx * ny > 2 * std::int64_t(n) + 16) {  // a thin or sparse box: coarser cells
    size *= 2;
    nx = std::int64_t(span.x() / size) + 1;
    ny = std::int64_t(span.y() / size) + 1;
  }
  // The cell of each particle, counted into cells.
  std::vector<std::int64_t> cx(n), cy(n);
  std::vector<int> cell_start(std::size_t(nx * ny) + 1, 0), order(n);
  for (int i = 0; i < n; ++i) {
    cx[i] = std::min<std::int64_t>(std::int64_t((x(0, i) - lo.x()) / size), nx - 1);
    cy[i] = std::min<std::int64_t>(std::int64_t((x(1, i) - lo.y()) / size), ny - 1);
    ++cell_start[std::size_t(cy[i] * nx + cx[i]) + 1];
  }
  for (std::size_t c = 1; c < cell_start.size(); ++c) cell_start[c] += cell_start[c - 1];
  std::vector<int> fill(cell_start.begin(), cell_start.end() - 1);
  for (int i = 0; i < n; ++i) order[std::size_t(fill[std::size_t(cy[i] * nx + cx[i])]++)] = i;
  // Each cell against itself and four of its neighbours (right, and the three
  // above), so that every pair of neighbouring cells is visited once.
  auto emit = [&](int i, int j) {
    const double reach = radius[i] + radius[j];
    if (std::abs(x(0, i) - x(0, j)) <= reach && std::abs(x(1, i) - x(1, j)) <= reach) {
      pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
  };
  const std::int64_t offsets[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};
  for (std::int64_t gy = 0; gy < ny; ++gy) {
    for (std::int64_t gx = 0; gx < nx; ++gx) {
      const std::size_t c = std::size_t(gy * nx + gx);
      const int begin = cell_start[c], end = cell_start[c + 1];
      if (begin == end) continue;
      for (int a = begin; a < end; ++a) {
        for (int b = a + 1; b < end; ++b) emit(order[std::size_t(a)], order[std::size_t(b)]);
      }
      for (const auto& o : offsets) {
        const std::int64_t hx = gx + o[0], hy = gy + o[1];
        if (hx < 0 || hx >= nx || hy >= ny) continue;
        const std::size_t d = std::size_t(hy * nx + hx);
        for (int a = begin; a < end; ++a) {
          for (int b = cell_start[d]; b < cell_start[d + 1]; ++b) {
            emit(order[std::size_t(a)], order[std::size_t(b)]);
          }
        }
      }
    }
  }
}
