// The collision phase: broad phase, narrow phase, impulses, as the lecture's
// loop forces -> integration -> collision detection -> collision response.
#include "contact_world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <tuple>

#include "collide_particles.h"
#include "collide_plane.h"
#include "contact_solver.h"
#include "friction_impulse.h"
#include "grid_pairs.h"
#include "wb/budget.h"

namespace wb {

namespace {

const Range kNonNegative{0.0};
const Range kPositive{0.0, std::numeric_limits<double>::infinity(), true};
const Range kUnit{0.0, 1.0};

using Clock = std::chrono::steady_clock;

// Contact skin (m): discs are handed to C1/C2 this much larger, so that a
// contact a previous pass left exactly touching is still a contact when
// rounding puts it a hair apart (else its approach would not be stopped).
constexpr double kSkin = 1e-9;

// The accumulated solver: a contact that pushed in the last step (Pn > 0) lasts while
// its gap is below this fraction of the smaller radius, so that a resting contact is
// not lost to rounding; overlap beyond the same slop is removed by moving positions,
// kPushBeta of it per step.
constexpr double kSlopFraction = 0.01;
constexpr double kPushBeta = 0.2;
constexpr int kAccumulatedIterations = 10;  // default "iterations" of the accumulated solver
// The cost model's rates of the collision phase (docs/scenes.md, "Cost"), measured
// with the solution's functions on the default scenes (the pile: 10^4 discs, 10.5
// ms per step): the phase's fixed work per step, the broad phase per particle
// (grid_pairs: 65 ns at 10^4 spread discs), per estimated candidate pair (the
// estimate counts cells 4 radii wide: grid_pairs reports about 2/5 of them, the
// narrow phase keeps most of those) its narrow test, the accumulated solver's
// bookkeeping (prepare, warm start, the kept totals' table), and its impulse in
// one pass or iteration; one particle against one plane in one pass.
constexpr double kSecondsPerContactStep = 0.3e-6;
constexpr double kSecondsPerBroadParticle = 40e-9;
constexpr double kSecondsPerCandidate = 10e-9;
constexpr double kSecondsPerKeptContact = 55e-9;
constexpr double kSecondsPerContactPass = 7e-9;
constexpr double kSecondsPerPlaneTest = 4e-9;
// Memory: the pair lists (grid_pairs reports about 2/5 of the estimate: 8 bytes
// each in the candidates and the contacts) up to the running check's limit, and a
// solved contact of the accumulated solver (its Contact, key and kept totals).
constexpr double kBytesPerEstimatedPair = 0.4 * 2 * 8;
constexpr double kBytesPerSolvedContact = 120;

// The stub warning compares grid_pairs (C3) with the brute force only up to this many
// particles: 4000^2 / 2 = 8e6 pair tests, a few milliseconds once per run.
constexpr Eigen::Index kWarnBruteForceMax = 4000;

// A length for a message: three significant digits (the run's numbers are in its outputs).
std::string three_digits(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

void brute_force_pairs(const Mat2X& x, const VecX& radius, Pairs& pairs) {
  pairs.clear();
  const int n = int(x.cols());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const double reach = radius[i] + radius[j];
      if (std::abs(x(0, i) - x(0, j)) <= reach && std::abs(x(1, i) - x(1, j)) <= reach) {
        pairs.emplace_back(i, j);
      }
    }
  }
}

void narrow_phase(const Mat2X& x, const VecX& radius, const Pairs& candidates, Pairs& contacts) {
  contacts.clear();
  const int n = int(x.cols());
  for (const auto& [i, j] : candidates) {
    if (i < 0 || j < 0 || i >= n || j >= n || i == j) continue;  // not a pair: ignored
    const double reach = radius[i] + radius[j] + 2 * kSkin;
    if ((x.col(i) - x.col(j)).squaredNorm() <= reach * reach) contacts.emplace_back(i, j);
  }
}

std::vector<PlaneDef> read_planes(const Scene& scene, ContactSettings& settings) {
  JsonObject top(scene.file, scene.doc, "");
  settings = ContactSettings{};
  if (top.has("contact")) {
    JsonObject c = top.object("contact");
    c.only_keys({"restitution", "friction", "iterations", "ccd", "resting_speed",
                 "shock_propagation", "solver"});
    settings.restitution = c.number_or("restitution", 1.0, kUnit);
    settings.friction = c.number_or("friction", 0.0, kNonNegative);
    settings.solver = Solver::kAccumulated;
    if (c.has("solver")) {
      const std::string name = c.string("solver");
      if (name == "passes") {
        settings.solver = Solver::kPasses;
      } else if (name != "accumulated") {
        c.fail("solver", &c.raw()["solver"], "one of: accumulated, passes");
      }
    }
    const int iterations = settings.solver == Solver::kPasses ? 1 : kAccumulatedIterations;
    settings.iterations = int(c.integer_or("iterations", iterations, 1, 1000));
    settings.ccd = c.boolean_or("ccd", false);
    settings.rest_speed = c.number_or("resting_speed", 0.0, kNonNegative);
    settings.shock = c.boolean_or("shock_propagation", false);
  }
  std::vector<PlaneDef> planes;
  const json& list = top.array_or_empty("planes");
  for (std::size_t k = 0; k < list.size(); ++k) {
    JsonObject o = top.element("planes", k);
    o.only_keys({"point", "normal", "restitution", "friction", "thickness"});
    PlaneDef p;
    p.point = o.vec2("point");
    // Scaled by its largest component before it is normalised (as the rigid
    // lab's normals), so that [1e200, 1e200] (whose norm overflows) and
    // [0, 3e-162] (whose squared norm is subnormal) give unit vectors too.
    const Vec2 n = o.vec2("normal");
    const double scale = n.cwiseAbs().maxCoeff();
    if (!(scale > 0)) {
      o.fail("normal", &o.raw().at("normal"), "a non-zero vector (it is normalised)");
    }
    p.n = (n / scale).normalized();
    p.restitution = o.number_or("restitution", settings.restitution, kUnit);
    p.friction = o.number_or("friction", settings.friction, kNonNegative);
    p.thickness = o.number_or("thickness", std::numeric_limits<double>::infinity(), kPositive);
    planes.push_back(p);
  }
  return planes;
}

namespace {

// The estimate on cells given as doubles (any finite positions): sorted, grouped,
// each group's neighbours found by binary search. O(n log n).
double pairs_on_sorted_cells(const Mat2X& x, double size) {
  const Eigen::Index n = x.cols();
  std::vector<std::pair<double, double>> cells(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    cells[std::size_t(i)] = {std::floor(x(1, i) / size), std::floor(x(0, i) / size)};
  }
  std::sort(cells.begin(), cells.end());
  // (cell, count), sorted by cell.
  std::vector<std::pair<std::pair<double, double>, double>> groups;
  for (const auto& c : cells) {
    if (groups.empty() || groups.back().first != c) {
      groups.push_back({c, 1.0});
    } else {
      groups.back().second += 1.0;
    }
  }
  const auto count = [&](double row, double col) {
    const auto it = std::lower_bound(
        groups.begin(), groups.end(), std::make_pair(row, col),
        [](const auto& g, const std::pair<double, double>& c) { return g.first < c; });
    return it != groups.end() && it->first == std::make_pair(row, col) ? it->second : 0.0;
  };
  double total = 0;
  for (const auto& [cell, c] : groups) {
    total += c * (c - 1) / 2;
    const auto [row, col] = cell;
    total += c * (count(row, col + 1) + count(row + 1, col - 1) + count(row + 1, col) +
                  count(row + 1, col + 1));
  }
  return total;
}

// The same on integer cells (|cell| < 2^30 in each coordinate), counted in a
// hash table: O(n), what the broad phase's running check can afford every step.
double pairs_on_hashed_cells(const Mat2X& x, double size) {
  const Eigen::Index n = x.cols();
  constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
  std::size_t slots = 16;
  while (slots < 2 * std::size_t(n)) slots *= 2;
  std::vector<std::uint64_t> keys(slots, kEmpty);
  std::vector<double> counts(slots, 0.0);
  const auto key = [](std::int64_t row, std::int64_t col) {
    return (std::uint64_t(row + (std::int64_t(1) << 31)) << 32) |
           std::uint64_t(col + (std::int64_t(1) << 31));
  };
  const auto slot = [&](std::uint64_t k) {
    std::size_t s = std::size_t((k * 0x9e3779b97f4a7c15ULL) >> 20) & (slots - 1);
    while (keys[s] != kEmpty && keys[s] != k) s = (s + 1) & (slots - 1);
    return s;
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::uint64_t k =
        key(std::int64_t(std::floor(x(1, i) / size)), std::int64_t(std::floor(x(0, i) / size)));
    const std::size_t s = slot(k);
    keys[s] = k;
    counts[s] += 1.0;
  }
  const auto count = [&](std::int64_t row, std::int64_t col) {
    const std::size_t s = slot(key(row, col));
    return keys[s] == kEmpty ? 0.0 : counts[s];
  };
  double total = 0;
  for (std::size_t s = 0; s < slots; ++s) {
    if (keys[s] == kEmpty) continue;
    const double c = counts[s];
    const auto row = std::int64_t(keys[s] >> 32) - (std::int64_t(1) << 31);
    const auto col = std::int64_t(keys[s] & 0xffffffffULL) - (std::int64_t(1) << 31);
    total += c * (c - 1) / 2;
    total += c * (count(row, col + 1) + count(row + 1, col - 1) + count(row + 1, col) +
                  count(row + 1, col + 1));
  }
  return total;
}

}  // namespace

double candidate_pairs_estimate(const Mat2X& x, const VecX& radius) {
  const Eigen::Index n = x.cols();
  if (n < 2 || !(radius.maxCoeff() > 0)) return 0;
  // Cells as wide as the largest grown diameter (a radius plus a margin of at
  // most the largest radius), as grid_pairs may use. Positions whose cells are
  // beyond 2^30 (discs near 1e308) are counted on cells kept as doubles: no
  // conversion of a huge quotient to an integer.
  const double size = 4 * radius.maxCoeff();
  const double reach = std::max(std::abs(x.minCoeff()), std::abs(x.maxCoeff())) / size;
  if (reach < 0x1p30 - 2) return pairs_on_hashed_cells(x, size);
  return pairs_on_sorted_cells(x, size);
}

double pairs_per_step(const Scene& scene) {
  if (scene.n() < 2 || !(scene.radius.maxCoeff() > 0)) return 0;
  return candidate_pairs_estimate(scene.x, scene.radius);
}

void check_radii(const Scene& scene) {
  // The collision phase forms 4 max(radius) (its cells), r_i + r_j and (r_i + r_j)^2
  // (the narrow phase), and moves particles by overlaps: all finite and resolvable
  // below kMaxRadius.
  for (Eigen::Index i = 0; i < scene.n(); ++i) {
    if (scene.radius[i] <= kMaxRadius) continue;
    throw InputError(scene.file + ": " + particle_key(scene, i) + ".radius: got " +
                     num(scene.radius[i]) +
                     ", expected a radius of at most 1e150 m (the collision phase squares sums "
                     "of radii: 4 max(radius) and (r_i + r_j)^2 must stay finite)");
  }
}

// The shortest text that reads back as x (a subnormal mass as the scene wrote it, 1e-308,
// not num's 17 digits 9.9999999999999991e-309).
static std::string shortest(double x) {
  char buf[32];
  for (int digits = 1; digits < 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    if (std::strtod(buf, nullptr) == x) return buf;
  }
  return num(x);
}

void check_effective_masses(const Scene& scene) {
  // Two particles that touch divide their impulse by 1/m_i + 1/m_j (C2, C5) and share a
  // push-out by it: a sum that overflows (two discs of 1e-308 kg) would make every impulse
  // 0 and the discs pass through each other, a run that looks like a stub. Pairs that can
  // touch: a disc with a disc, or with a particle of radius 0.
  Eigen::Index a = -1, b = -1, z = -1;  // the two lightest discs, the lightest point
  for (Eigen::Index i = 0; i < scene.n(); ++i) {
    if (!(scene.radius[i] > 0)) {
      if (z < 0 || scene.m[i] < scene.m[z]) z = i;
    } else if (a < 0 || scene.m[i] < scene.m[a]) {
      b = a, a = i;
    } else if (b < 0 || scene.m[i] < scene.m[b]) {
      b = i;
    }
  }
  if (a < 0) return;
  for (const Eigen::Index j : {b, z}) {
    if (j < 0 || std::isfinite(1 / scene.m[a] + 1 / scene.m[j])) continue;
    const Eigen::Index light = scene.m[j] < scene.m[a] ? j : a, other = light == a ? j : a;
    throw InputError(scene.file + ": " + particle_key(scene, light) + ".m: got " +
                     shortest(scene.m[light]) +
                     ", expected masses whose sum of inverses "
                     "1/m_i + 1/m_j is finite for particles that can touch (with " +
                     particle_key(scene, other) + ", m = " + shortest(scene.m[other]) +
                     ", it overflows: their impulses would be 0)");
  }
}

InitialOverlaps initial_overlaps(const Mat2X& x, const VecX& radius,
                                 const std::vector<PlaneDef>& planes) {
  InitialOverlaps o;
  const auto note = [&](double depth, int a, int b) {
    if (!(depth > kSkin)) return;  // touching is not overlapping (and NaN is neither)
    ++o.count;
    if (depth > o.deepest) o.deepest = depth, o.a = a, o.b = b;
  };
  const Eigen::Index n = x.cols();
  for (Eigen::Index i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < planes.size(); ++k) {
      const PlaneDef& p = planes[k];
      const double d = (x.col(i) - p.point).dot(p.n);
      if (d < -p.thickness) continue;  // beyond a thin wall's back face: not in contact
      note(radius[i] - d, int(i), -1 - int(k));
    }
  }
  if (n < 2 || !(radius.maxCoeff() > 0)) return o;
  // The pairs of a uniform grid of cells 4 max(radius) wide, as candidate_pairs_estimate
  // counts them (one step's broad phase as the cost model estimates it), the particles
  // sorted by cell.
  const double size = 4 * radius.maxCoeff();
  std::vector<std::tuple<double, double, int>> cells(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    cells[std::size_t(i)] = {std::floor(x(1, i) / size), std::floor(x(0, i) / size), int(i)};
  }
  std::sort(cells.begin(), cells.end());
  const auto first_in = [&](double row, double col) {
    return std::lower_bound(cells.begin(), cells.end(), std::make_tuple(row, col, -1));
  };
  const auto test = [&](int i, int j) {
    note(radius[i] + radius[j] - (x.col(i) - x.col(j)).norm(), std::min(i, j), std::max(i, j));
  };
  for (auto it = cells.begin(); it != cells.end(); ++it) {
    const auto [row, col, i] = *it;
    for (auto jt = std::next(it);
         jt != cells.end() && std::get<0>(*jt) == row && std::get<1>(*jt) == col; ++jt)
      test(i, std::get<2>(*jt));
    // The forward neighbours, each once and never the particle's own cell: beyond 2^53
    // cells from the origin col + 1 == col (discs near 1e308), and a cell that is its
    // own neighbour would test every particle in it against itself.
    std::pair<double, double> next[4];
    int count = 0;
    for (const std::pair<double, double>& cell : {std::pair<double, double>{row, col + 1},
                                                  {row + 1, col - 1},
                                                  {row + 1, col},
                                                  {row + 1, col + 1}}) {
      if (cell == std::make_pair(row, col) || std::find(next, next + count, cell) != next + count)
        continue;
      next[count++] = cell;
    }
    for (int q = 0; q < count; ++q) {
      const auto [r, c] = next[q];
      for (auto jt = first_in(r, c);
           jt != cells.end() && std::get<0>(*jt) == r && std::get<1>(*jt) == c; ++jt)
        test(i, std::get<2>(*jt));
    }
  }
  return o;
}

ContactWorld::ContactWorld(const Scene& scene)
    : forces_(scene), m_(scene.m), r_(scene.radius), x_prev_(scene.x) {
  check_radii(scene);
  check_effective_masses(scene);
  planes_ = read_planes(scene, settings_);
  w_ = m_.cwiseInverse();
  any_radius_ = r_.size() > 0 && r_.maxCoeff() > 0;
  // The running check of the broad phase's work (docs/scenes.md, "Cost").
  pairs_ = WorkMeter(scene.file, "candidate pairs (estimated)",
                     std::max(pairs_per_step(scene), kPilePairs * double(scene.n())),
                     "the particles crowd together far more than in their initial state "
                     "(a pile of equal discs has about " +
                         num(kPilePairs) +
                         " per particle); spread them out, use fewer, or smaller radii");
  // A scene that starts with overlaps is said once, with the count and the deepest.
  const InitialOverlaps o = initial_overlaps(scene.x, r_, planes_);
  if (o.count > 0) {
    const std::string with =
        o.b >= 0
            ? "particles " + std::to_string(o.a) + " and " + std::to_string(o.b)
            : "particle " + std::to_string(o.a) + " and planes[" + std::to_string(-1 - o.b) + "]";
    initial_notes_.push_back(scene.file + ": " + std::to_string(o.count) +
                             (o.count == 1 ? " overlap" : " overlaps") +
                             " at t = 0 (discs with discs or planes), the deepest " +
                             three_digits(o.deepest) + " m (" + with +
                             "): the collision phase pushes them apart by moving positions "
                             "only, which adds no kinetic energy");
  }
  // "Up" for the stacking pass: against the sum of the uniform gravity terms
  // (each already checked by ForceWorld), summed scaled by 2^-30 so that the
  // sum of large ones does not overflow, and normalised after dividing by its
  // largest component.
  Vec2 g = Vec2::Zero();
  for (const auto& f : scene.doc.value("forces", json::array())) {
    if (f.value("type", "") == "gravity")
      g += 0x1p-30 * Vec2(f["g"][0].get<double>(), f["g"][1].get<double>());
  }
  const double gmax = g.cwiseAbs().maxCoeff();
  if (gmax > 0 && std::isfinite(gmax)) up_ = -(g / gmax).normalized();
}

// Continuous check (provided): a particle that was in front of a thin wall at
// the previous step and is now beyond its back face crossed it during the
// step. It is put back where its path first touched the wall (time of
// impact, linear in the step) and its normal velocity is reflected with the
// wall's restitution; the rest of that step's motion is dropped.
void ContactWorld::continuous_check(Mat2X& x, Mat2X& v) const {
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    for (const PlaneDef& p : planes_) {
      if (!std::isfinite(p.thickness)) continue;  // a half-space cannot be crossed
      const double before = (x_prev_.col(i) - p.point).dot(p.n) - r_[i];
      const double after = (x.col(i) - p.point).dot(p.n) - r_[i];
      if (!(before >= 0 && after + r_[i] < -p.thickness)) continue;
      const double toi = before / (before - after);  // fraction of the step, in [0, 1)
      x.col(i) = x_prev_.col(i) + toi * (x.col(i) - x_prev_.col(i));
      const double vn = v.col(i).dot(p.n);
      if (vn < 0) v.col(i) -= (1 + p.restitution) * vn * p.n;
    }
  }
}

void ContactWorld::after_step(double h, Mat2X& x, Mat2X& v) const {
  if (!(x.allFinite() && v.allFinite())) return;  // diverged: the run loop reports it
  const bool timing = timing_;
  Clock::time_point t0;
  if (settings_.ccd) continuous_check(x, v);

  // Broad phase (C3), then the exact test.
  // Pairs within a margin are kept too: the response of one contact can push
  // a particle into a neighbour it did not touch after the integration, and
  // that contact must be in the list for the next pass to see it. The margin
  // is the distance two particles close in one step (2 h max |v|), at most
  // the largest radius.
  contacts_.clear();
  pairs_.next_step();
  const budget::PhaseScope phase(budget::kPairs);
  if (any_radius_ && x.cols() >= 2) {
    if (timing) t0 = Clock::now();
    const double margin =
        std::min(2 * h * std::sqrt(v.colwise().squaredNorm().maxCoeff()), r_.maxCoeff());
    r_grown_ = r_.array() + margin;
    // The work the broad phase may do, counted before it is done (and so before
    // its pairs are allocated) when all pairs together could pass the limit.
    const double n = double(x.cols());
    if (pairs_.over(n * (n - 1) / 2)) pairs_.count(candidate_pairs_estimate(x, r_grown_));
    // grid_pairs is handed positions whose span, plus the largest diameter,
    // is finite in each coordinate. Positions near +-1e308 (or radii near it)
    // are scaled by 1/8 first (span / 8 + 4 radii / 8 < 1.8e308): an exact
    // power of two, so the pairs it finds are the same (|x_i - x_j| <= r_i + r_j
    // scales exactly for normal numbers).
    const Vec2 span = x.rowwise().maxCoeff() - x.rowwise().minCoeff();
    const double reach = 2 * r_grown_.maxCoeff();
    if ((span.array() + reach).allFinite()) {
      grid_pairs(x, r_grown_, candidates_);
      if (timing) times_.broad += seconds_since(t0), t0 = Clock::now();
      narrow_phase(x, r_grown_, candidates_, contacts_);
    } else {
      x_scaled_ = 0.125 * x;
      r_scaled_ = 0.125 * r_.array() + 0.125 * margin;
      grid_pairs(x_scaled_, r_scaled_, candidates_);
      if (timing) times_.broad += seconds_since(t0), t0 = Clock::now();
      narrow_phase(x_scaled_, r_scaled_, candidates_, contacts_);
    }
    if (timing) times_.narrow += seconds_since(t0);
  }

  // Response: a fixed number of passes over the contacts, then the planes.
  budget::set_phase(budget::kContacts);
  if (timing) t0 = Clock::now();
  if (settings_.solver == Solver::kAccumulated) {
    accumulated(h, x, v);
    if (timing) times_.response += seconds_since(t0);
    x_prev_ = x;
    return;
  }
  const double e = settings_.restitution;
  for (int it = 0; it < settings_.iterations; ++it) {
    for (const auto& [i, j] : contacts_) pair_response(h, i, m_[j], j, e, x, v);
    planes_pass(h, x, v);
  }
  if (settings_.shock && up_.norm() > 0) shock_pass(h, x, v);
  if (timing) times_.response += seconds_since(t0);
  x_prev_ = x;
}

void ContactWorld::planes_pass(double h, Mat2X& x, Mat2X& v) const {
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    for (const PlaneDef& p : planes_) {
      // Beyond a thin wall's back face: no contact (it tunnelled).
      if ((x.col(i) - p.point).dot(p.n) < -p.thickness) continue;
      const Vec2 x0 = x.col(i), v0 = v.col(i);
      Vec2 xi = x0, vi = v0;
      const double jn = collide_plane(p.point, p.n, r_[i] + kSkin, m_[i], p.restitution,
                                      settings_.rest_speed, xi, vi);
      const bool approaching =
          (x0 - p.point).dot(p.n) < r_[i] && v0.dot(p.n) < -settings_.rest_speed;
      plane_hits_.seen += approaching;
      plane_hits_.answered += approaching && jn > 0;
      if (jn > 0) {
        if (p.friction > 0) {
          const Vec2 before = vi;
          const double jt = friction_impulse(p.n, jn, p.friction, m_[i], vi);
          const bool sliding = (before - before.dot(p.n) * p.n).norm() > 0;
          friction_hits_.seen += sliding;
          friction_hits_.answered += sliding && (jt != 0 || vi != before);
        }
        // The impulses act before this step's position update: x0 + h dv,
        // then only what overlap remains is removed (a second call with no
        // velocity moves without an impulse).
        xi = x0 + h * (vi - v0);
        Vec2 still = Vec2::Zero();
        collide_plane(p.point, p.n, r_[i] + kSkin, m_[i], 0.0, 0.0, xi, still);
      }
      x.col(i) = xi, v.col(i) = vi;
    }
  }
}

// Shock propagation (Guendelman, Bridson and Fedkiw 2003, for stacks): one
// last pass, planes first, then the contacts from the bottom up, each with
// its lower particle treated as a wall (mass 10^9 times its own, so that the
// impulse law needs no special case). The support of the floor then reaches
// the top of a stack in one pass, instead of spreading by halves per pass.
void ContactWorld::shock_pass(double h, Mat2X& x, Mat2X& v) const {
  planes_pass(h, x, v);
  // The contacts by the height of their lower particle (keys computed once).
  order_.resize(contacts_.size());
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    const auto& [a, b] = contacts_[c];
    const double h_low = std::min(x.col(a).dot(up_), x.col(b).dot(up_));
    // A NaN key (a state that is diverging) would break std::sort's ordering.
    order_[c] = {std::isnan(h_low) ? std::numeric_limits<double>::infinity() : h_low, int(c)};
  }
  std::sort(order_.begin(), order_.end());
  sorted_.resize(contacts_.size());
  for (std::size_t c = 0; c < order_.size(); ++c)
    sorted_[c] = contacts_[std::size_t(order_[c].second)];
  contacts_.swap(sorted_);
  constexpr double kWall = 1e9;  // mass factor of the lower particle
  for (const auto& [a, b] : contacts_) {
    const bool a_low = x.col(a).dot(up_) <= x.col(b).dot(up_);
    const int lo = a_low ? a : b, hi = a_low ? b : a;
    const Vec2 x_lo = x.col(lo), v_lo = v.col(lo);
    pair_response(h, hi, kWall * m_[lo], lo, settings_.restitution, x, v);
    x.col(lo) = x_lo, v.col(lo) = v_lo;  // the lower one does not move
  }
  planes_pass(h, x, v);  // nothing ends the step inside a wall
}

// One contact through collide_particles (C2), j's mass given. As at planes,
// the impulse acts before this step's position update (x0 + h dv), and a
// second call without velocities removes what overlap remains.
void ContactWorld::pair_response(double h, int i, double mj, int j, double e, Mat2X& x,
                                 Mat2X& v) const {
  const Vec2 x1_0 = x.col(i), v1_0 = v.col(i), x2_0 = x.col(j), v2_0 = v.col(j);
  Vec2 x1 = x1_0, v1 = v1_0, x2 = x2_0, v2 = v2_0;
  const double J = collide_particles(m_[i], r_[i] + kSkin, mj, r_[j] + kSkin, e, x1, v1, x2, v2);
  const Vec2 d = x1_0 - x2_0;
  const bool approaching = d.norm() < r_[i] + r_[j] && (v1_0 - v2_0).dot(d) < 0;
  pair_hits_.seen += approaching;
  pair_hits_.answered += approaching && J > 0;
  if (J > 0) {
    x1 = x1_0 + h * (v1 - v1_0);
    x2 = x2_0 + h * (v2 - v2_0);
    Vec2 s1 = Vec2::Zero(), s2 = Vec2::Zero();
    collide_particles(m_[i], r_[i] + kSkin, mj, r_[j] + kSkin, 0.0, x1, s1, x2, s2);
  }
  x.col(i) = x1, v.col(i) = v1, x.col(j) = x2, v.col(j) = v2;
}

// The accumulated solver (C5): this step's contacts, each with the totals it kept
// from the last step, in two phases.
//   Impacts, one at a time: `iterations` passes over the contacts with e > 0; each one
//   closing faster than resting_speed gets C5's one-shot impulse (prepare_contact on
//   the current velocities with no stored totals, then one solve_contact): the
//   restitution law on its current approach, as C1 and C2 apply it. Each such impulse
//   reflects one contact's normal velocity (times e), so an elastic impact keeps the
//   kinetic energy exactly however many contacts meet in one step. Solved together
//   instead, with restitution targets taken before the step, a cluster of contacts
//   (discs that touch two others at once, overlaps at t = 0) ends its iterations off
//   the targets and gains or loses energy: +0.9 % for an elastic gas in 50 steps.
//   Contacts, together: prepare every contact on the velocities the impacts left,
//   warm start with the last step's totals, `iterations` passes of solve_contact;
//   these totals carry resting contact from step to step and are kept.
// The impulses act before this step's position update (x0 + h dv); then what overlap
// is left beyond the slop is removed by moving positions only.
void ContactWorld::accumulated(double h, Mat2X& x, Mat2X& v) const {
  // Keys: a * M + b for a pair, a * M + n + k for particle a and plane k.
  const std::uint64_t n = std::uint64_t(x.cols()), M = n + planes_.size();
  solved_.clear();
  keys_.clear();
  restitution_.clear();
  plane_.clear();
  // A contact is new when the discs overlap (or touch), and lasts while it pushed in the
  // last step and the gap is below the slop.
  const auto add = [&](int a, int b, const Vec2& normal, double gap, double slop, double mu,
                       double e, std::uint64_t k) {
    const auto it = kept_.find(k);
    const bool held = it != kept_.end() && it->second.first > 0;
    if (!(gap <= kSkin || (held && gap < slop))) return;
    Contact c;
    c.a = a, c.b = b, c.n = normal, c.mu = mu;
    if (it != kept_.end()) c.Pn = it->second.first, c.Pt = it->second.second;
    solved_.push_back(c);
    keys_.push_back(k);
    restitution_.push_back(e);
    plane_.push_back(b >= 0 ? -1 : int(k % M - n));
  };
  for (const auto& [i, j] : contacts_) {
    const Vec2 d = x.col(i) - x.col(j);
    const double dist = d.norm();
    const Vec2 normal = dist > 0 ? Vec2(d / dist) : Vec2(0.0, 1.0);
    add(i, j, normal, dist - r_[i] - r_[j], kSlopFraction * std::min(r_[i], r_[j]), 0.0,
        settings_.restitution, std::uint64_t(i) * M + std::uint64_t(j));
  }
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    for (std::size_t k = 0; k < planes_.size(); ++k) {
      const PlaneDef& p = planes_[k];
      const double gap = (x.col(i) - p.point).dot(p.n) - r_[i];
      if (gap + r_[i] < -p.thickness) continue;  // beyond a thin wall's back face
      add(int(i), -1, p.n, gap, kSlopFraction * r_[i], p.friction, p.restitution,
          std::uint64_t(i) * M + n + k);
    }
  }
  const Mat2X v0 = v;
  impacted_.assign(solved_.size(), 0);
  // Impacts, one at a time (only scenes with restitution pay for this phase).
  const bool elastic =
      std::any_of(restitution_.begin(), restitution_.end(), [](double e) { return e > 0; });
  for (int it = 0; elastic && it < settings_.iterations; ++it) {
    for (std::size_t c = 0; c < solved_.size(); ++c) {
      if (!(restitution_[c] > 0)) continue;
      Contact one = solved_[c];
      one.Pn = 0, one.Pt = 0;
      prepare_contact(w_, v, restitution_[c], settings_.rest_speed, one);
      if (!(one.bias > 0)) continue;  // not an impact (any more)
      impacted_[c] |= solve_contact(w_, one, v) > 0;
    }
  }
  // Contacts, together.
  for (std::size_t c = 0; c < solved_.size(); ++c) {
    prepare_contact(w_, v, restitution_[c], settings_.rest_speed, solved_[c]);
  }
  for (const Contact& c : solved_) warm_start_contact(w_, c, v);
  for (int it = 0; it < settings_.iterations; ++it) {
    for (Contact& c : solved_) solve_contact(w_, c, v);
  }
  x += h * (v - v0);
  // The totals, for the next step's warm start; approaching contacts that the
  // solver (C5) left without a normal impulse are counted for warnings().
  kept_.clear();
  for (std::size_t c = 0; c < solved_.size(); ++c) {
    const Contact& k = solved_[c];
    const Vec2 rel = k.b >= 0 ? Vec2(v0.col(k.a) - v0.col(k.b)) : Vec2(v0.col(k.a));
    const bool approaching = rel.dot(k.n) < 0;
    solver_hits_.seen += approaching;
    solver_hits_.answered += approaching && (k.Pn > 0 || impacted_[c]);
    kept_[keys_[c]] = {k.Pn, k.Pt};
  }
  push_apart(x);
}

// Overlap beyond the slop, removed by moving positions only (no velocity changes, so no
// energy is added): kPushBeta of it per contact, shared in proportion to 1/m, a few
// Gauss-Seidel passes.
void ContactWorld::push_apart(Mat2X& x) const {
  for (int pass = 0; pass < 4; ++pass) {
    for (std::size_t k = 0; k < solved_.size(); ++k) {
      const Contact& c = solved_[k];
      if (c.b >= 0) {
        const Vec2 d = x.col(c.a) - x.col(c.b);
        const double dist = d.norm();
        const double slop = kSlopFraction * std::min(r_[c.a], r_[c.b]);
        const double s = r_[c.a] + r_[c.b] - dist - slop;
        if (!(s > 0) || !(dist > 0)) continue;
        const Vec2 nn = d / dist;
        const double wa = w_[c.a], wb = w_[c.b];
        x.col(c.a) += kPushBeta * s * wa / (wa + wb) * nn;
        x.col(c.b) -= kPushBeta * s * wb / (wa + wb) * nn;
      } else {
        const PlaneDef& p = planes_[std::size_t(plane_[k])];
        const double s = r_[c.a] - (x.col(c.a) - p.point).dot(p.n) - kSlopFraction * r_[c.a];
        if (s > 0) x.col(c.a) += kPushBeta * s * p.n;
      }
    }
  }
}

std::vector<std::string> ContactWorld::warnings(const Mat2X& x, const Mat2X& v) const {
  std::vector<std::string> out = forces_.warnings(x, v);
  // With the forces lab's stubs, gravity pulls nothing down: a ball floats above its
  // floor, no contact ever happens, and the collision functions are never called. Say
  // so, or a student who starts with this lab reads only about the forces lab.
  const bool touched = plane_hits_.seen + pair_hits_.seen + solver_hits_.seen > 0;
  if (!out.empty() && !touched && (!planes_.empty() || x.cols() >= 2)) {
    out.push_back(
        "no particle reached a plane or another particle, so the collision functions "
        "(C1-C5) were never called and this run tests none of them: the scene's forces "
        "gave no force (the warning above), so nothing moved the particles into contact. "
        "Write the forces lab's gravity (F1) and accumulate_forces first, or start a "
        "particle moving towards a plane (its \"v\")");
  }
  auto unanswered = [&](const Answered& a, const std::string& what) {
    if (a.seen > 0 && a.answered == 0) {
      out.push_back(std::to_string(a.seen) + " times " + what +
                    " returned no impulse for any of them: is it still a stub?");
    }
  };
  unanswered(plane_hits_,
             "a particle moved into a plane within its radius, and collide_plane (C1)");
  unanswered(pair_hits_,
             "two touching particles moved towards each other, and "
             "collide_particles (C2)");
  unanswered(solver_hits_,
             "a contact closed in, and the contact solver (C5: prepare_contact, "
             "warm_start_contact, solve_contact)");
  unanswered(friction_hits_,
             "a particle slid along a plane with friction, and "
             "friction_impulse (C4)");
  // The broad phase (C3) against the provided brute force, on the last state: only
  // where the brute force is cheap (n^2 / 2 pair tests) and grid_pairs is handed
  // what the step hands it (a span that does not overflow, see after_step).
  const double reach = x.cols() > 0 ? 4 * r_.maxCoeff() : 0.0;
  const bool spans_finite =
      x.allFinite() &&
      ((x.rowwise().maxCoeff() - x.rowwise().minCoeff()).array() + reach).allFinite();
  if (any_radius_ && x.cols() >= 2 && x.cols() <= kWarnBruteForceMax && spans_finite) {
    Pairs grid, brute;
    grid_pairs(x, r_, grid);
    brute_force_pairs(x, r_, brute);
    if (grid.empty() && !brute.empty()) {
      out.push_back(
          "grid_pairs (C3) found no candidate pair in the last state, where the "
          "brute-force broad phase finds " +
          std::to_string(brute.size()) + ": is it still a stub?");
    }
  }
  return out;
}

void contact_step_cost(const Scene& scene, const Integrator& it, StepCost& c) {
  forces_step_cost(scene, it, c);
  if (!scene.doc.contains("planes") && !scene.doc.contains("contact")) return;
  ContactSettings settings;
  const std::vector<PlaneDef> planes = read_planes(scene, settings);
  const double n = double(scene.n()), np = double(planes.size());
  const double pairs = pairs_per_step(scene);
  const bool accumulated = settings.solver == Solver::kAccumulated;
  const double passes = settings.iterations + (settings.shock ? 2 : 0) + (settings.ccd ? 1 : 0);
  const std::string iters =
      " x " + std::to_string(settings.iterations) + (accumulated ? " iterations" : " passes");
  c.step.add("collision phase: its fixed work", "", 1, kSecondsPerContactStep);
  c.step.add("broad phase: " + std::to_string(scene.n()) + " particles", "particles", n,
             kSecondsPerBroadParticle);
  if (pairs > 0) {
    c.step.add("candidate pairs: about " + num(std::round(pairs)) + " per step", "particles",
               pairs, kSecondsPerCandidate,
               kOverrunFactor * std::max(pairs, kPilePairs * n) * kBytesPerEstimatedPair +
                   (accumulated ? pairs * kBytesPerSolvedContact : 0.0));
    c.step.add("contact impulses: " + num(std::round(pairs)) + " candidate pairs" + iters,
               "contact.iterations", pairs * settings.iterations, kSecondsPerContactPass);
    if (accumulated) {
      c.step.add("contact bookkeeping: " + num(std::round(pairs)) + " candidate pairs",
                 "particles", pairs, kSecondsPerKeptContact);
    }
  }
  if (np > 0) {
    c.step.add("plane tests: " + std::to_string(scene.n()) + " particles x " + num(np) +
                   " planes x " + num(accumulated ? 1 : passes) + " passes",
               "planes", n * np * (accumulated ? 1 : passes), kSecondsPerPlaneTest);
  }
}

void use_collisions(LabInfo& info) {
  use_forces(info);
  info.step_cost = contact_step_cost;
  info.scene_keys.push_back("planes");
  info.scene_keys.push_back("contact");
  info.make_world = [](const Scene& scene) -> std::unique_ptr<World> {
    // A scene pays only for what it declares: no planes, no contact block, no collisions.
    if (!scene.doc.contains("planes") && !scene.doc.contains("contact")) {
      return std::make_unique<ForceWorld>(scene);
    }
    return std::make_unique<ContactWorld>(scene);
  };
  info.help_sections.push_back(
      "Collision keys (docs/scenes.md#collisions):\n"
      "  planes:  [{\"point\": [x, y], \"normal\": [nx, ny], \"restitution\": e, \"friction\": "
      "mu,\n"
      "            \"thickness\": t}]   (normal is normalised; solid side behind it)\n"
      "  contact: {\"restitution\": e, \"friction\": mu, \"iterations\": k, \"ccd\": bool,\n"
      "            \"resting_speed\": s, \"shock_propagation\": bool,\n"
      "            \"solver\": \"accumulated\" | \"passes\"}\n"
      "           (defaults 1, 0, 10 (accumulated) or 1 (passes), false, 0, false,\n"
      "           accumulated: C5's warm-started impulses; passes: C1, C2, C4 pass after pass)\n"
      "  particles and emitters take \"radius\" (default 0). Without planes or contact, no\n"
      "  collisions are computed.\n");
}

}  // namespace wb
