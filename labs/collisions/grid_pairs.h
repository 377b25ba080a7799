// TODO(C3) broad phase on a uniform grid. Handout: handouts/collisions.md#c3. Tests: [C3].
#pragma once
#include <utility>
#include <vector>

#include "wb/types.h"

// The candidate pairs for the narrow phase: every pair (i, j), i < j, whose
// bounding boxes overlap, touching included:
//
//   |x_i - x_j| <= r_i + r_j   and   |y_i - y_j| <= r_i + r_j
//
// computed EXACTLY like this (same expressions), so that the set equals the one
// of the provided brute force wb::brute_force_pairs (O(n^2), in
// framework/drivers/collisions/contact_world.h), but in O(n) for evenly spread
// particles of similar size: put every particle in the cell of a uniform grid
// that holds its centre, with cells at least as wide as the largest diameter,
// and test each particle only against the particles of its own and the
// neighbouring cells.
//
// Inputs:
//   x       2 x n centres (m); any coordinates, negative ones too (the
//           collision phase makes sure that max - min of each coordinate, plus
//           the largest diameter, is finite: positions near +-1e308 are scaled)
//   radius  n radii (m), >= 0 (mixed sizes allowed; all zero allowed)
// Outputs:
//   pairs   cleared, then every overlapping pair once, as (i, j) with i < j, in
//           any order
void grid_pairs(const wb::Mat2X& x, const wb::VecX& radius,
                std::vector<std::pair<int, int>>& pairs);
