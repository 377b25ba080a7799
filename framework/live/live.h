// The live pages' simulation (docs/live.md): one scene stepped on demand from a
// page's knobs by the same lab code as the native executable, with the run
// contract's divergence rule (wb/contract.h). The page (tools/wbview/live/page/) draws
// and turns knobs; everything physical happens here and in the lab's files.
//
// A lab joins without a line of its own: a live build compiles the lab's main.cpp
// with main renamed (cmake/live.cmake), and the run_particle_lab / run_rigid_lab
// that main() calls keep a copy of its LabInfo instead of running
// (particle_live.cpp, framework/drivers/rigid/live/).
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "wb/contract.h"

namespace wb::live {

// The numbers the page reads after every frame, in this order (Sim::readouts).
enum Readout {
  kT,          // simulated time (s)
  kSteps,      // steps taken since the last reset
  kKinetic,    // kinetic energy (J)
  kPotential,  // potential energy (J)
  kEnergy,     // their sum (J)
  kPx,         // linear momentum (kg m/s), x y z (z 0 in 2D)
  kPy,
  kPz,
  kLx,  // angular momentum about the origin (kg m^2/s), x y z (2D: z only)
  kLy,
  kLz,
  kEvals,        // force evaluations since the last reset
  kUnconverged,  // steps whose implicit solve did not converge since the last reset
  kExactDist,    // largest distance from the exact motion (m), NaN when there is none
  kCount
};

// How hard the cursor pulls what it grabbed: a spring-damper to the cursor of this
// frequency (Hz) and damping ratio, solved implicitly (Box2D's mouse joint), so that
// it is stable at any step.
constexpr double kGrabHz = 5.0;
constexpr double kGrabDamping = 0.7;
// A grabbed particle is pulled as if it carried up to this many times its mass (the
// particles hanging on it: particle_live.cpp).
constexpr double kGrabLoad = 50.0;

// One scene being stepped. Errors in a scene or a change are wb::InputError.
class Sim {
 public:
  virtual ~Sim() = default;
  // Loads a scene from its JSON text (`file` names it in messages): the initial
  // state, the world, the scale of the divergence rule, the scene's integrator.
  virtual void load(const std::string& file, const std::string& text) = 0;
  // The same scene with other parameters (the page's knobs): a new world from the
  // text; the current state is kept when the count of particles or bodies is the
  // same, else the new scene starts from its initial state.
  virtual void update(const std::string& text) = 0;
  // Back to the scene's initial state, step 0.
  virtual void reset() = 0;
  // The integrator called `name` (InputError when there is none, or when it cannot
  // run this scene: Integrator::check).
  virtual void set_integrator(const std::string& name) = 0;
  // Up to n steps of size h; stops after the first diverged step (diverged()). Returns
  // the steps taken.
  virtual long step(double h, long n) = 0;
  // The state, as the trace writes it (docs/run-contract.md): x y vx vy per particle,
  // or x y z qw qx qy qz vx vy vz wx wy wz per body.
  virtual const std::vector<double>& state() = 0;
  virtual int values_per_item() const = 0;
  // The readouts (enum Readout), kCount numbers.
  virtual const std::vector<double>& readouts() = 0;
  // The exact positions now (2 per particle), empty when the scene has no closed form
  // or the run left it (a grab, a changed parameter: until the next reset).
  virtual const std::vector<double>& exact() = 0;
  // Pull item i (a particle, or body i's point `at_body`, body frame) towards the world
  // point `target` in every step until release(). 2D labs read target[0..1].
  virtual void grab(long i, const double* target, const double* at_body) = 0;
  virtual void release() = 0;
  // The run's words for the page: its integrator, why it diverged (the contract's
  // sentence) and at which step, the stub warnings and the world's notes (JSON).
  virtual std::string status() const = 0;
};

// What the page asks of a lab before any scene: its name, side, kind ("particles" or
// "rigid") and integrators (JSON), and how to make a Sim.
struct LabEntry {
  std::string lab, side;
  std::string info;  // JSON object
  std::function<std::unique_ptr<Sim>()> make;
};

// Called by a lab's main() through run_particle_lab or run_rigid_lab in a live build.
void add_lab(LabEntry e);
// Every lab registered so far (a live module registers one; the native benchmark, all).
const std::vector<LabEntry>& labs();

// The run contract's bookkeeping of a live run, whatever its state: steps, time, the
// divergence rule (wb::divergence on the energy scale of the scene's initial state)
// and the unconverged solves (wb::unconverged_divergence, as if the run ended now).
struct Contract {
  double scale = 0;       // the energy scale E_s of the divergence rule (J)
  long steps = 0;         // steps since the last reset
  double t = 0;           // sum of the steps' h (s)
  std::string diverged;   // the contract's sentence, "" while it has not diverged
  long diverged_at = -1;  // the step it diverged at
  void restart(double energy_scale) {
    *this = Contract{};
    scale = energy_scale;
  }
  // After one step of size h: applies the rule; returns false once diverged.
  bool after_step(double h, bool finite, double energy);
  void check_unconverged(long unconverged);
};

// The cursor's spring-damper on an item of mass m (kg) for a step h, as a soft
// constraint (Box2D's mouse joint): stiffness m w^2 and damping 2 m zeta w at
// w = 2 pi kGrabHz, zeta = kGrabDamping. The impulse on the grabbed point is
// P = -K^-1 (v_p + beta (p - target)), with K its inverse mass (matrix) plus gamma:
// gamma (1/kg) and beta (1/s) are set here.
void grab_coefficients(double h, double m, double& gamma, double& beta);

// The status JSON's common part (diverged, step, warnings).
std::string status_json(const Contract& c, const std::string& integrator,
                        const std::vector<std::string>& warnings,
                        const std::vector<std::string>& notes, const std::string& error);

}  // namespace wb::live
