// One force term of a particle system, as built from a scene's "forces" list.
#pragma once
#include <string>

#include "wb/types.h"

namespace wb {

class Force {
 public:
  virtual ~Force() = default;
  // Adds this term's force on every particle to f (2 x n). Never resizes f.
  //   x, v: positions and velocities (2 x n); m: masses (n).
  virtual void add(const Mat2X& x, const Mat2X& v, const VecX& m, Mat2X& f) const = 0;
  // Potential energy of a conservative term at x; 0 for the others.
  virtual double potential(const Mat2X& /*x*/, const VecX& /*m*/) const { return 0.0; }
  // The scene "type" this term was built from ("gravity", "spring", ...).
  virtual std::string type() const = 0;
};

}  // namespace wb
