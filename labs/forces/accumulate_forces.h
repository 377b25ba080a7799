// TODO(F6) accumulate all forces. Handout: handouts/forces.md#f6. Tests: [F6].
#pragma once
#include <memory>
#include <vector>

#include "wb/force.h"
#include "wb/types.h"

// The total force on every particle: the sum of every term in `forces`.
// f may come in with any size and any contents (last step's forces, say):
// on return it is 2 x n and holds exactly the sum.
//
// Inputs:
//   forces  the scene's force terms; each term's add() adds its share to f
//   x, v    2 x n positions (m) and velocities (m/s)
//   m       n masses (kg)
// Outputs:
//   f       2 x n total forces (N)
void accumulate_forces(const std::vector<std::unique_ptr<wb::Force>>& forces, const wb::Mat2X& x,
                       const wb::Mat2X& v, const wb::VecX& m, wb::Mat2X& f);
