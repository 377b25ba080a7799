// A deterministic, seeded, smooth 2D noise and the potential psi(x) built from
// it for curl noise (forces lab F9). Provided: students take the curl of psi,
// they do not write the noise. Header-only and light (Eigen/Core only), so
// that the lab, its glue and its tests can all use it.
//
// The noise is gradient ("Perlin") noise: at every integer lattice point a unit
// gradient chosen by a hash of (i, j, seed), blended across each cell with the
// quintic fade 6t^5 - 15t^4 + 10t^3 (so the noise is twice continuously
// differentiable and its curl is smooth). It is 0 on the lattice points.
#pragma once
#include <cmath>
#include <cstdint>
#include <functional>

#include "wb/types.h"

namespace wb {

// A scalar potential psi(x) (m^2/s): the flow is its curl, u = (dpsi/dy, -dpsi/dx).
using Potential = std::function<double(const Vec2&)>;

namespace noise_detail {

// splitmix64's finaliser: every input bit changes every output bit.
inline std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

inline double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

// The unit gradient at lattice point (i, j): one of 16 directions.
inline Vec2 lattice_gradient(std::int64_t i, std::int64_t j, std::uint64_t seed) {
  static const double kDir[16][2] = {{1.0, 0.0},
                                     {0.9238795325, 0.3826834324},
                                     {0.7071067812, 0.7071067812},
                                     {0.3826834324, 0.9238795325},
                                     {0.0, 1.0},
                                     {-0.3826834324, 0.9238795325},
                                     {-0.7071067812, 0.7071067812},
                                     {-0.9238795325, 0.3826834324},
                                     {-1.0, 0.0},
                                     {-0.9238795325, -0.3826834324},
                                     {-0.7071067812, -0.7071067812},
                                     {-0.3826834324, -0.9238795325},
                                     {0.0, -1.0},
                                     {0.3826834324, -0.9238795325},
                                     {0.7071067812, -0.7071067812},
                                     {0.9238795325, -0.3826834324}};
  const std::uint64_t h =
      mix(mix(seed ^ 0x9e3779b97f4a7c15ULL) ^ mix(std::uint64_t(i) * 0xd1b54a32d192ed03ULL) ^
          std::uint64_t(j) * 0x8cb92ba72f3d8dd7ULL);
  const int k = int(h >> 60);
  return Vec2(kDir[k][0], kDir[k][1]);
}

}  // namespace noise_detail

// Gradient noise at p (in lattice units), seeded: the same (p, seed) gives the
// same value on every platform. Values lie in about [-0.7, 0.7]. Beyond 2^52
// lattice units every double is a lattice point, where the noise is 0: it is 0
// there (and for a p that is not finite) without converting the coordinate to an
// integer, which would be undefined past 2^63.
inline double gradient_noise(const Vec2& p, std::uint64_t seed) {
  constexpr double kLatticeLimit = 0x1p52;
  if (!(std::abs(p.x()) < kLatticeLimit && std::abs(p.y()) < kLatticeLimit)) return 0.0;
  const double fx = std::floor(p.x()), fy = std::floor(p.y());
  const auto i = std::int64_t(fx), j = std::int64_t(fy);
  const double tx = p.x() - fx, ty = p.y() - fy;  // position inside the cell, in [0, 1)
  auto corner = [&](std::int64_t di, std::int64_t dj) {
    return noise_detail::lattice_gradient(i + di, j + dj, seed)
        .dot(Vec2(tx - double(di), ty - double(dj)));
  };
  const double sx = noise_detail::fade(tx), sy = noise_detail::fade(ty);
  const double bottom = corner(0, 0) + sx * (corner(1, 0) - corner(0, 0));
  const double top = corner(0, 1) + sx * (corner(1, 1) - corner(0, 1));
  return bottom + sy * (top - bottom);
}

// The root-mean-square of |grad gradient_noise| over the plane (measured over
// 10^6 random points for three seeds: 0.883). Dividing by it makes `amplitude` the
// root-mean-square speed of the flow.
constexpr double kNoiseGradientRms = 0.883;

// The curl-noise potential of a scene's "curl-noise" force (docs/scenes.md):
//   psi(x) = amplitude * scale * N(x / scale) / kNoiseGradientRms
//            + wind.x * y - wind.y * x
// N the gradient noise above with `seed`. Its curl is a flow whose speed is
// about `amplitude` (m/s) on average, whose swirls are about `scale` (m)
// across, plus the uniform `wind` (m/s).
inline Potential noise_potential(std::uint64_t seed, double amplitude, double scale,
                                 const Vec2& wind = Vec2::Zero()) {
  const double k = amplitude * scale / kNoiseGradientRms;
  return [=](const Vec2& x) {
    return k * gradient_noise(x / scale, seed) + wind.x() * x.y() - wind.y() * x.x();
  };
}

}  // namespace wb
