#include "grid_pairs.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

// Correct, a spatial hash: cells keyed by their integer coordinates in a hash
// map (no bounding box, no dense array), each particle against the 3 x 3 cells
// around its own.
void grid_pairs(const wb::Mat2X& x, const wb::VecX& radius,
                std::vector<std::pair<int, int>>& pairs) {
  pairs.clear();
  const int n = int(x.cols());
  if (n < 2) return;
  const double size = std::max(2 * radius.maxCoeff() * (1 + 1e-9), 1e-3);
  auto cell = [&](double c) { return std::int64_t(std::floor(c / size)); };
  auto key = [](std::int64_t cx, std::int64_t cy) {
    return std::uint64_t(cx) * 0x9E3779B97F4A7C15ull ^ std::uint64_t(cy);
  };
  std::unordered_map<std::uint64_t, std::vector<int>> cells;
  std::vector<std::int64_t> cx(n), cy(n);
  for (int i = 0; i < n; ++i) {
    cx[i] = cell(x(0, i));
    cy[i] = cell(x(1, i));
    cells[key(cx[i], cy[i])].push_back(i);
  }
  for (int i = 0; i < n; ++i) {
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        auto it = cells.find(key(cx[i] + dx, cy[i] + dy));
        if (it == cells.end()) continue;
        for (int j : it->second) {
          // Different cells may share a key: the cell check keeps each pair once.
          if (j <= i || cx[j] != cx[i] + dx || cy[j] != cy[i] + dy) continue;
          const double reach = radius[i] + radius[j];
          if (std::abs(x(0, i) - x(0, j)) <= reach && std::abs(x(1, i) - x(1, j)) <= reach) {
            pairs.emplace_back(i, j);
          }
        }
      }
    }
  }
}
