// What a lab's glue builds from a scene for the run contract: the
// accelerations an integrator sees, the energy the summary reports, and an
// optional phase after every step (collisions). The core knows no lab: each
// lab's glue (framework/drivers/<lab>/) makes its own World.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "wb/dynamics.h"
#include "wb/force.h"
#include "wb/scene.h"

namespace wb {

struct Energy {
  double kinetic = 0, potential = 0;
  double total() const { return kinetic + potential; }
};

// Total linear momentum sum m_i v_i (kg m/s).
inline Vec2 momentum(const Mat2X& v, const VecX& m) { return v * m; }

class World {
 public:
  virtual ~World() = default;
  // The accelerations a(x, v) that integrators step with.
  virtual const Dynamics& dynamics() const = 0;
  // Kinetic and potential energy at (x, v).
  virtual Energy energy(const Mat2X& x, const Mat2X& v) const = 0;
  // The scene's force terms, each with its key and bound (check_initial_state
  // checks the initial forces and potentials term by term). Default: none.
  virtual std::vector<const Force*> terms() const { return {}; }
  // Called after every integrator step of size h, before the state is
  // recorded (collision detection and response). The default does nothing.
  virtual void after_step(double /*h*/, Mat2X& /*x*/, Mat2X& /*v*/) const {}
  // Plain sentences for the summary's "warnings" at the end of a run, ending
  // in (x, v): what a stub of the lab's functions did that would otherwise
  // pass for a result (a contact no function answered). The default: none.
  virtual std::vector<std::string> warnings(const Mat2X& /*x*/, const Mat2X& /*v*/) const {
    return {};
  }
  // Plain sentences about a run that are not what a stub does (an implicit
  // solve that did not converge on some steps): printed on stderr as warnings
  // at the end of the run, not in the summary's "warnings" (which mean a stub).
  virtual std::vector<std::string> notes() const { return {}; }
  // Plain sentences about the scene itself, said once on stderr as warnings before
  // the run (or sweep) starts: a scene that starts with overlapping discs. Not in
  // the summary's "warnings" either. The default: none.
  virtual std::vector<std::string> initial_notes() const { return {}; }
};

// Builds a scene's World; throws InputError for bad scene entries.
using WorldFactory = std::function<std::unique_ptr<World>(const Scene&)>;

}  // namespace wb
