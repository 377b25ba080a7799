#include "grid_pairs.h"

#include <algorithm>
#include <cmath>
#include <numeric>

// Correct, sort and sweep (no grid): particles sorted by the left end of their
// box, x - r; each one is tested against the following ones until their left
// ends pass its right end x + r (with a hair of slack for rounding: the exact
// test below decides).
void grid_pairs(const wb::Mat2X& x, const wb::VecX& radius,
                std::vector<std::pair<int, int>>& pairs) {
  pairs.clear();
  const int n = int(x.cols());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> lo(n);
  for (int i = 0; i < n; ++i) lo[i] = x(0, i) - radius[i];
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lo[a] < lo[b]; });
  for (int a = 0; a < n; ++a) {
    const int i = order[a];
    const double hi = x(0, i) + radius[i];
    const double slack = 1e-12 * (1 + std::abs(hi));
    for (int b = a + 1; b < n && lo[order[b]] <= hi + slack; ++b) {
      const int j = order[b];
      const double reach = radius[i] + radius[j];
      if (std::abs(x(0, i) - x(0, j)) <= reach && std::abs(x(1, i) - x(1, j)) <= reach) {
        pairs.emplace_back(std::min(i, j), std::max(i, j));
      }
    }
  }
}
