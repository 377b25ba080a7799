// The rigid lab's glue: a 3D scene of rigid bodies (docs/scenes.md, "rigid"),
// the step that calls the student's functions, the trace rows and the sweep's
// errors. Everything else of the run contract (the main, flags, cost model,
// outputs, step loop, sweep loop, summary line) is the particle labs' code, in
// wb/lab.h and wb/contract.h (rigid_run.cpp is this lab's wb::LabScene); only the
// state is its own (rigid::Body, 3D).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "plane_contact.h"
#include "rigid_body.h"
#include "wb/cost.h"
#include "wb/input.h"

namespace rigid {

// One body as the scene declares it: its shape (for the contact points) and
// its initial state (I_body from the student's R1 functions).
struct BodyDef {
  enum Shape { kBox, kSphere, kCylinder } shape = kBox;
  Vec3 size = Vec3::Ones();  // box: full edge lengths (m)
  double radius = 0.5;       // sphere, cylinder (m)
  double length = 1.0;       // cylinder, along body z (m)
  Body body;                 // initial state
};

struct Plane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // unit
};

// A joint to the world: a point (ball) joint, or, with "axis", a revolute hinge.
struct Hinge {
  int body = 0;
  Vec3 anchor = Vec3::Zero();      // world point (m)
  Vec3 r_body = Vec3::Zero();      // the pinned point of the body, body frame (m)
  double beta = 0.2;               // drift correction per step
  bool revolute = false;           // true when the scene gives "axis"
  Vec3 axis = Vec3::UnitZ();       // revolute: the hinge axis, world (unit)
  Vec3 axis_body = Vec3::UnitZ();  // revolute: the same axis in the body frame at the start
};

// How contacts with planes are solved ("contact": {"solver": ...}).
enum class Solver {
  kPasses,       // one-shot impulses, passes until none applies, then a push-out (provided)
  kAccumulated,  // accumulated, warm-started impulses (R6) and split-impulse push-out
};

// A constant world force applied at a point fixed in a body.
struct PointForce {
  int body = 0;
  Vec3 point_body = Vec3::Zero();  // body frame, from the centre (m)
  Vec3 F = Vec3::Zero();           // world frame (N)
};

struct Scene {
  std::string file, name;
  std::optional<double> dt, t_end;
  std::optional<std::string> integrator;
  std::vector<BodyDef> bodies;
  Vec3 g = Vec3::Zero();  // sum of the "gravity" forces (m/s^2)
  std::vector<PointForce> point_forces;
  std::vector<Plane> planes;
  double restitution = 0.3, friction = 0.5;
  // The new solver whenever the scene has a "contact" block, the passes otherwise.
  Solver solver = Solver::kPasses;
  int iterations = 10;       // accumulated: iterations per step
  double rest_speed = 0.05;  // accumulated: closing speeds (m/s) below this do not bounce
  std::vector<Hinge> hinges;
  bool torque_free() const {
    return g.isZero(0) && point_forces.empty() && planes.empty() && hinges.empty();
  }
};

// Reads and checks a scene file; throws wb::InputError naming the key.
Scene load_scene(const std::string& file);
// The same checks on a parsed document (`file` names it in the messages):
// every accepted scene has finite numbers, 1/m finite, an inertia scale
// m d^2 within [1e-290, 1e290] and finite initial totals (docs/scenes.md).
Scene scene_from_json(const std::string& file, const wb::json& doc);
// A scene whose bodies start inside a plane: one sentence with the count of (body, plane)
// pairs and the deepest point (the contact pushes them out by positions only, push_out);
// none otherwise. Said once before the run (after the cost model accepted the scene).
std::vector<std::string> initial_overlap_notes(const Scene& s);

// The work of the scene's initial forces across it (J), sum of (m |g| + |F|) times the
// scene's size (the extent of the centres or their largest distance from the origin,
// 1 m when both are 0): the floor of the divergence rule's energy scale. Finite for
// every scene the loader accepts.
double work_scale_of(const Scene& scene);

// The update of (v, omega) an integrator stands for (the student's R5 functions).
using VelocityStep = void (*)(Body&, double);
struct Integrator {
  std::string name;
  VelocityStep velocity;
  std::string description;
};

// A point that pushed on a plane in the last step still counts as touching it while it
// is less than this above it (m), so that a resting contact is not lost to rounding.
// The passes solver counts every point this close as touching.
constexpr double kContactSlop = 1e-3;
constexpr int kContactPasses = 10;  // the passes solver: at most this many passes
// Split impulses: the push-out removes this fraction of the penetration per step.
constexpr double kPushBeta = 0.2;

// What a run keeps from one step to the next: every body's contacts with every plane,
// indexed by candidate point, with their accumulated impulses (warm starting).
struct StepState {
  std::vector<std::vector<Contact>> contacts;  // [body * planes + plane][point]
  double hinge_angle = 0;  // after the last step: the largest angle between a revolute
                           // hinge's body axis and its axis (rad)
  // Has a velocity update (forces and R5, before the constraints) changed any body's
  // velocity or angular velocity in some step? What the run's stub warnings ask.
  bool velocity_changed = false;
};

// One whole step of every body: forces, velocities, hinges, contacts, positions.
// Returns the largest hinge drift |x + R r_body - anchor| after the step (m).
double step(const Scene& scene, const Integrator& integ, double h, std::vector<Body>& bodies,
            StepState& state);
// The same without warm starting across calls (a fresh state each time).
double step(const Scene& scene, const Integrator& integ, double h, std::vector<Body>& bodies);

// The provided one-shot solver ("solver": "passes"): an impulse at each approaching
// point with restitution and friction, passes until none applies, then the body is
// pushed out by its deepest penetration. Returns the sum of the normal impulses.
double resolve_plane_passes(Body& b, const std::vector<Vec3>& points, const Vec3& point,
                            const Vec3& n, double e, double mu);

// Diagnostics (the glue's own formulas, not the student's).
struct Totals {
  double kinetic = 0, potential = 0;
  Vec3 p = Vec3::Zero(), L = Vec3::Zero();  // momentum, angular momentum about the origin
  double energy() const { return kinetic + potential; }
};
Totals totals(const Scene& scene, const std::vector<Body>& bodies);

// The floor of a run's energy scale (wb::energy_scale): the work gravity and the point
// forces would do across the scene (work_scale_of, finite by the loader); the run's
// and the live page's divergence rule both read it.
double work_scale(const Scene& scene, const std::vector<Body>& bodies);

// The contact candidates of a body against a plane (world points).
std::vector<Vec3> contact_points(const BodyDef& def, const Body& b, const Plane& plane);

// The cost model's terms of a rigid scene (docs/scenes.md, "Cost"): its bodies,
// hinges and contact tests per step, from the scene's numbers.
void step_cost(const Scene& scene, wb::StepCost& c);

struct LabInfo {
  std::string lab, side, summary;
  std::vector<Integrator> integrators;  // the first is the default
};

// main() of the rigid lab: the run contract (docs/run-contract.md) for 3D bodies.
int run_rigid_lab(int argc, char** argv, const LabInfo& info);

}  // namespace rigid
