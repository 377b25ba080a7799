// Graded tests for C3, the grid broad phase (labs/collisions/grid_pairs.cpp).
// Expected values: the pair set of an O(n^2) brute force over the header's
// formula (every pair is tested, so its set is right by construction; the
// same expressions as the provided wb::brute_force_pairs), and for a square
// lattice of touching discs the count of its 8-neighbour links.
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

#include "grid_pairs.h"
#include "heldout.h"
#include "test_helpers.h"

// A lab's test files compile as one unit (cmake/labs.cmake): each keeps its
// helpers in a namespace of its own.
namespace test_C3_grid_pairs {

namespace {

using Pairs = std::vector<std::pair<int, int>>;

// Every pair i < j whose boxes overlap, touching included (grid_pairs.h).
void brute_force(const wb::Mat2X& x, const wb::VecX& radius, Pairs& pairs) {
  pairs.clear();
  for (int i = 0; i < int(x.cols()); ++i) {
    for (int j = i + 1; j < int(x.cols()); ++j) {
      const double reach = radius[i] + radius[j];
      if (std::abs(x(0, i) - x(0, j)) <= reach && std::abs(x(1, i) - x(1, j)) <= reach) {
        pairs.emplace_back(i, j);
      }
    }
  }
}

// Compares grid_pairs with brute force: same pairs, each once, i < j.
void require_same_pairs(const wb::Mat2X& x, const wb::VecX& r, const std::string& what) {
  Pairs got = {{1, 0}, {5, 3}}, expected;  // left from a previous step: cleared first
  grid_pairs(x, r, got);
  brute_force(x, r, expected);
  for (const auto& [i, j] : got) {
    INFO(what << ": grid_pairs gave (" << i << ", " << j << "), expected i < j, both < "
              << x.cols() << " (the vector held (1, 0) and (5, 3) before the call: clear it)");
    REQUIRE((0 <= i && i < j && j < x.cols()));  // nanfree: integers
  }
  Pairs sorted = got;
  std::sort(sorted.begin(), sorted.end());
  const bool unique = std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
  Pairs missing, extra;
  std::set_difference(expected.begin(), expected.end(), sorted.begin(), sorted.end(),
                      std::back_inserter(missing));
  std::set_difference(sorted.begin(), sorted.end(), expected.begin(), expected.end(),
                      std::back_inserter(extra));
  std::ostringstream s;
  s << what << ": brute force finds " << expected.size() << " pairs, grid_pairs " << got.size()
    << " (the vector is cleared first: it held 2 pairs before the call)";
  if (!missing.empty()) {
    s << "; missing (" << missing[0].first << ", " << missing[0].second << ") at "
      << wbtest::str(x.col(missing[0].first)) << " r " << r[missing[0].first] << " and "
      << wbtest::str(x.col(missing[0].second)) << " r " << r[missing[0].second];
  }
  if (!extra.empty()) s << "; extra (" << extra[0].first << ", " << extra[0].second << ")";
  if (!unique) s << "; a pair is listed twice";
  INFO(s.str());
  REQUIRE(missing.empty());
  REQUIRE(extra.empty());
  REQUIRE(unique);
}

// n radii uniform in [lo, hi), from a fixed seed (the mapping to doubles is ours).
wb::VecX random_radii(Eigen::Index n, std::uint64_t seed, double lo, double hi) {
  std::mt19937_64 gen(seed);
  wb::VecX r(n);
  for (Eigen::Index i = 0; i < n; ++i) r[i] = lo + (hi - lo) * (double(gen() >> 11) * 0x1.0p-53);
  return r;
}

}  // namespace

TEST_CASE("C3 grid_pairs: same pair set as brute force on random scenes of mixed radii",
          "[collisions][C3][5pts]") {
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    const Eigen::Index n = 400;
    const wb::Mat2X x = wbtest::random_points(n, seed, -3.0, 2.0);  // negative coordinates too
    wb::VecX r = random_radii(n, 100 + seed, 0.01, 0.15);
    for (Eigen::Index i = 0; i < n; i += 7) r[i] = 0.0;  // some points among the discs
    require_same_pairs(x, r, "random scene, seed " + std::to_string(seed));
  }
  // Clustered: a dense patch in a sparse field.
  wb::Mat2X x(2, 300);
  x << wbtest::random_points(200, 9, 0.0, 0.5), wbtest::random_points(100, 10, -40.0, 40.0);
  require_same_pairs(x, random_radii(300, 11, 0.02, 0.06), "dense patch in a sparse field");
}

TEST_CASE("C3 grid_pairs: a lattice of touching discs on cell boundaries",
          "[collisions][C3][4pts]") {
  // k x k centres 2r apart (exact in binary), from -1 upwards: every disc
  // touches its neighbours and each box touches its diagonal neighbours'
  // corners, so the pairs are the lattice's 8-neighbour links:
  //   2 k (k - 1) horizontal and vertical, 2 (k - 1)^2 diagonal.
  for (double r : {0.125, 0.25}) {
    const int k = 12;
    wb::Mat2X x(2, k * k);
    for (int a = 0; a < k; ++a) {
      for (int b = 0; b < k; ++b) x.col(a * k + b) = wb::Vec2(-1.0 + 2 * r * a, -1.0 + 2 * r * b);
    }
    const wb::VecX radius = wb::VecX::Constant(k * k, r);
    Pairs got;
    grid_pairs(x, radius, got);
    INFO("a 12 x 12 lattice of touching discs of radius "
         << r << " on cell boundaries: expected " << 2 * k * (k - 1) + 2 * (k - 1) * (k - 1)
         << " pairs (every 8-neighbour link: touching boxes count), got " << got.size()
         << " (fewer: a neighbour cell left out, or a strict < where touching must count; "
            "more: a pair listed twice)");
    REQUIRE(got.size() == std::size_t(2 * k * (k - 1) + 2 * (k - 1) * (k - 1)));
    require_same_pairs(x, radius, "lattice of touching discs, r = " + std::to_string(r));
  }
}

TEST_CASE("C3 grid_pairs: zero radii and one large disc among small ones and far outliers",
          "[collisions][C3][3pts]") {
  {
    // Points (radius 0): only coincident ones pair up; none, one and two particles.
    wb::Mat2X x(2, 6);
    x << 0.5, -0.25, 0.5, 3.0, -0.25, 0.5, 1.0, 2.0, 1.0, 0.0, 2.0, 1.0;
    require_same_pairs(x, wb::VecX::Zero(6), "points with coincident copies");
    Pairs got;
    grid_pairs(x, wb::VecX::Zero(6), got);
    INFO(
        "points of radius 0 pair only where they coincide: {0, 2, 5} give 3 pairs and "
        "{1, 4} one, 4 in all; got "
        << got.size() << " (a pair listed twice, or a point paired with itself?)");
    REQUIRE(got.size() == 4);  // {0, 2, 5} coincide (3 pairs), {1, 4} (1 pair)
    grid_pairs(wb::Mat2X(2, 0), wb::VecX(0), got);
    INFO("no particles give no pairs, and `pairs` is cleared first; got " << got.size());
    REQUIRE(got.empty());
    grid_pairs(x.leftCols(1), wb::VecX::Constant(1, 0.3), got);
    INFO("one particle gives no pairs (never a particle with itself); got " << got.size());
    REQUIRE(got.empty());
  }
  {
    const Eigen::Index n = 300;
    wb::Mat2X x = wbtest::random_points(n, 21, -1.0, 1.0);
    wb::VecX r = random_radii(n, 22, 0.005, 0.03);
    r[n - 1] = 0.6;                      // one large disc
    x.col(n - 2) = wb::Vec2(1e6, -1e6);  // far outliers
    x.col(n - 3) = wb::Vec2(1e6 + 0.01, -1e6);
    require_same_pairs(x, r, "one large disc and two far outliers");
  }
}

TEST_CASE("C3 held-out: random scenes of mixed radii give the brute force's pair set",
          "[collisions][C3][held-out][3pts]") {
  for (wbtest::HeldOut& g : wbtest::held_out("C3")) {
    INFO(g.replay());
    for (int s = 0; s < 4; ++s) {
      const Eigen::Index n = s == 3 ? g.integer(40, 60) : g.integer(20, 60);
      wb::Mat2X x(2, n);
      wb::VecX radius(n);
      if (s == 3) {
        // Dense: discs of about one radius R in a box R sqrt(n) / 2 wide, so that the box
        // alone asks for cells narrower than R: many pairs lie between R and 2R apart, in
        // cells two apart when the cells are narrower than the largest diameter.
        const double R = g.log_uniform(0.1, 10.0), side = R * std::sqrt(double(n)) / 2;
        const wb::Vec2 origin = g.vec2(-100, 100) * R;
        for (Eigen::Index i = 0; i < n; ++i) {
          radius[i] = R * g.uniform(0.8, 1.0);
          x.col(i) = origin + side * g.vec2(0, 1);
        }
      } else if (s == 0) {
        // A lattice of touching discs of one radius (binary fractions, offset at random by
        // whole spacings): boxes touch exactly on the cells' boundaries.
        const double r = g.integer(1, 8) / 16.0;
        const long cols = g.integer(3, 8);
        const wb::Vec2 origin(2 * r * double(g.integer(-20, 20)),
                              2 * r * double(g.integer(-20, 20)));
        for (Eigen::Index i = 0; i < n; ++i) {
          x.col(i) = origin + 2 * r * wb::Vec2(double(i % cols), double(i / cols));
          radius[i] = r;
        }
      } else {
        // Mixed radii (some zero, one large), spread in a box a few diameters wide, some far.
        const double scale = g.log_uniform(0.1, 10.0);
        for (Eigen::Index i = 0; i < n; ++i) {
          radius[i] = g.coin(0.1) ? 0.0 : scale * g.uniform(0.05, 0.5);
          x.col(i) = scale * g.vec2(-3, 3);
        }
        radius[g.integer(0, n - 1)] = scale * g.uniform(1.0, 3.0);
        x.col(g.integer(0, n - 1)) = scale * g.vec2(-100, 100);
        x.col(g.integer(0, n - 1)) = x.col(g.integer(0, n - 1));  // two at the same place
      }
      Pairs expected;
      brute_force(x, radius, expected);
      // The output comes in full of last call's pairs: it must be cleared.
      Pairs got = {{0, 1}, {2, 3}, {int(n) - 2, int(n) - 1}};
      grid_pairs(x, radius, got);
      for (const auto& pr : got) {
        INFO("pair (" << pr.first << ", " << pr.second << "): expected 0 <= i < j < " << n);
        REQUIRE((0 <= pr.first && pr.first < pr.second && pr.second < n));  // nanfree: integers
      }
      std::sort(got.begin(), got.end());
      std::sort(expected.begin(), expected.end());
      Pairs missing, extra;
      std::set_difference(expected.begin(), expected.end(), got.begin(), got.end(),
                          std::back_inserter(missing));
      std::set_difference(got.begin(), got.end(), expected.begin(), expected.end(),
                          std::back_inserter(extra));
      const bool repeated = std::adjacent_find(got.begin(), got.end()) != got.end();
      std::ostringstream what;
      what << (s == 0   ? "a lattice of touching discs"
               : s == 3 ? "dense discs"
                        : "mixed radii")
           << ", " << n << " discs: " << expected.size() << " pairs expected, " << got.size()
           << " found";
      if (!missing.empty())
        what << "; missing (" << missing[0].first << ", " << missing[0].second
             << "): x = " << wbtest::str(x.col(missing[0].first))
             << " r = " << radius[missing[0].first]
             << " and x = " << wbtest::str(x.col(missing[0].second))
             << " r = " << radius[missing[0].second];
      if (!extra.empty())
        what << "; not overlapping (" << extra[0].first << ", " << extra[0].second << ")";
      if (repeated) what << "; a pair found twice";
      INFO(what.str());
      REQUIRE(missing.empty());
      REQUIRE(extra.empty());
      REQUIRE_FALSE(repeated);
    }
  }
}

}  // namespace test_C3_grid_pairs
