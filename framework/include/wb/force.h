// One force term of a particle system, as built from a scene's "forces" list.
#pragma once
#include <string>

#include "wb/types.h"

namespace wb {

class Force {
 public:
  std::string key;  // the scene entry it was built from ("forces[2]"), for messages
  virtual ~Force() = default;
  // Adds this term's force on every particle to f (2 x n). Never resizes f.
  //   x, v: positions and velocities (2 x n); m: masses (n).
  virtual void add(const Mat2X& x, const Mat2X& v, const VecX& m, Mat2X& f) const = 0;
  // Potential energy of a conservative term at x; 0 for the others.
  virtual double potential(const Mat2X& /*x*/, const VecX& /*m*/) const { return 0.0; }
  // The scene "type" this term was built from ("gravity", "spring", ...).
  virtual std::string type() const = 0;
  // Adds to b[i] an upper bound of the largest component of this term's f_i (N)
  // at (x, v), from the term's own parameters (not the lab's functions), so that
  // a scene whose forces overflow is refused before the first step
  // (check_initial_state); the sum over the terms bounds the total. The default
  // adds nothing.
  virtual void bound(const Mat2X& /*x*/, const Mat2X& /*v*/, const VecX& /*m*/,
                     VecX& /*b*/) const {}
  // The scene entry to name when this term's bound or potential is not finite
  // at (x, v): `key`, unless the term gathers several entries (the springs).
  virtual std::string blame(const Mat2X& /*x*/, const Mat2X& /*v*/) const { return key; }
  // True when f_i depends only on x_i, v_i and m_i (and the term's parameters):
  // then a list of such terms can be evaluated a block of particles at a time
  // (wb::Dynamics::per_particle). False unless a term says so.
  virtual bool per_particle() const { return false; }
  // False when f does not depend on x (the term's add ignores it): uniform
  // gravity, damping. True unless a term says so.
  virtual bool reads_positions() const { return true; }
};

}  // namespace wb
