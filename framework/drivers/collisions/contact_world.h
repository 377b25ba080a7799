// The collisions lab's glue: a scene's "planes" and "contact" keys -> the
// collision phase that runs after every integrator step (wb::World::after_step),
// calling the student's functions: grid_pairs (C3, broad phase), then either the
// accumulated, warm-started solver (C5: prepare_contact, warm_start_contact,
// solve_contact on every contact together), or, for a fixed number of passes,
// collide_particles (C2) on the contacts and collide_plane (C1) + friction_impulse
// (C4) on every particle and plane.
// The forces are the forces lab's (ForceWorld). Keys: docs/scenes.md#collisions.
#pragma once
#include <cstdint>
#include <limits>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "contact_solver.h"
#include "forces_world.h"
#include "wb/run.h"
#include "wb/world.h"

namespace wb {

using Pairs = std::vector<std::pair<int, int>>;

// Provided reference broad phase, O(n^2): every (i, j), i < j, with
//   |x_i - x_j| <= r_i + r_j  and  |y_i - y_j| <= r_i + r_j,
// in lexicographic order. grid_pairs (C3) must find the same set.
void brute_force_pairs(const Mat2X& x, const VecX& radius, Pairs& pairs);

// Provided narrow phase: the candidate pairs whose discs touch or overlap,
// |x_i - x_j| <= r_i + r_j.
void narrow_phase(const Mat2X& x, const VecX& radius, const Pairs& candidates, Pairs& contacts);

// One "planes" entry. The solid side is behind n; with a finite thickness the
// solid is the slab of that thickness behind the surface (a thin wall), and a
// particle whose centre is beyond its back face is not in contact.
struct PlaneDef {
  Vec2 point = Vec2::Zero();
  Vec2 n = Vec2(0, 1);  // unit normal (normalised from the scene's "normal")
  double restitution = 1, friction = 0;
  double thickness = std::numeric_limits<double>::infinity();  // m
};

// How the contacts are resolved ("contact": {"solver": ...}).
enum class Solver {
  kPasses,       // one-shot impulses (C1, C2, C4) in passes, then overlap removed
  kAccumulated,  // accumulated, warm-started impulses (C5), then overlap removed
};

// The scene's "contact" block (defaults when it is left out).
struct ContactSettings {
  double restitution = 1;  // e for particle pairs and the default for planes
  double friction = 0;     // mu at planes (default for planes)
  // The accumulated solver whenever the scene has a "contact" block.
  Solver solver = Solver::kPasses;
  int iterations = 1;     // impulse passes (iterations) per step; 10 for accumulated
  bool ccd = false;       // continuous check of fast particles against planes
  double rest_speed = 0;  // "resting_speed": slower approaches do not bounce (m/s)
  bool shock = false;     // "shock_propagation": a last, bottom-up pass for stacks
};

// The collision phase's part of the cost model (docs/scenes.md, "Cost"): the
// candidate pairs it expects per step are the initial state's estimate, and at
// least kPilePairs per particle (discs of one radius piled up: a cell of 4 radii
// holds about 4.6 of them, so a particle meets about 21 in its own and the
// neighbouring cells). A step whose broad phase would pass kOverrunFactor times
// that stops the run (WorkMeter), before its pairs are made.
constexpr double kPilePairs = 24;
// A radius above this is refused: the phase forms 4 max(radius) and
// (r_i + r_j)^2, finite below 1e153 with room.
constexpr double kMaxRadius = 1e150;

// An upper bound of the pairs a uniform grid of cells 4 max(radius) wide
// tests (each particle against its own and the neighbouring cells), in
// O(n log n) time and O(n) memory, defined for any finite positions.
double candidate_pairs_estimate(const Mat2X& x, const VecX& radius);

// The candidate pairs per step the cost model expects of a scene (above).
double pairs_per_step(const Scene& scene);

// The cost model's terms of a collisions scene for one integrator: its forces
// (forces_step_cost) and the collision phase after every step.
void contact_step_cost(const Scene& scene, const Integrator& it, StepCost& c);

// Overlaps at t = 0 (docs/scenes.md, "collisions"): pairs of discs, and discs with planes,
// that overlap by more than the contact skin; the deepest (m) and what it joins (particles
// a < b, or particle a and plane -1 - b when b < 0). A scene that starts with overlaps warns
// once with the count and the deepest.
struct InitialOverlaps {
  long count = 0;
  double deepest = 0;
  int a = -1, b = -1;
};
InitialOverlaps initial_overlaps(const Mat2X& x, const VecX& radius,
                                 const std::vector<PlaneDef>& planes);

// Reads "planes" and "contact" (throws InputError naming the key).
std::vector<PlaneDef> read_planes(const Scene& scene, ContactSettings& settings);

// Where one collision step spends its time (seconds, accumulated), for the benchmark.
struct PhaseTimes {
  double broad = 0, narrow = 0, response = 0;
};

// Forces from the forces lab, then the collision phase after every step.
class ContactWorld : public World {
 public:
  explicit ContactWorld(const Scene& scene);
  const Dynamics& dynamics() const override { return forces_.dynamics(); }
  Energy energy(const Mat2X& x, const Mat2X& v) const override { return forces_.energy(x, v); }
  std::vector<const Force*> terms() const override { return forces_.terms(); }
  void after_step(double h, Mat2X& x, Mat2X& v) const override;
  // A stub's signature: contacts that approached and got no impulse from C1,
  // C2 or C4 in the whole run, a broad phase (C3) that misses pairs.
  std::vector<std::string> warnings(const Mat2X& x, const Mat2X& v) const override;
  // The scene's overlaps at t = 0, if any (initial_overlaps): one sentence.
  std::vector<std::string> initial_notes() const override { return initial_notes_; }

  const std::vector<PlaneDef>& planes() const { return planes_; }
  const ContactSettings& settings() const { return settings_; }
  // Accumulated phase times when timing is on (off by default: no clock reads).
  void set_timing(bool on) { timing_ = on; }
  const PhaseTimes& times() const { return times_; }

 private:
  void continuous_check(Mat2X& x, Mat2X& v) const;
  void planes_pass(double h, Mat2X& x, Mat2X& v) const;
  void shock_pass(double h, Mat2X& x, Mat2X& v) const;
  void pair_response(double h, int i, double mj, int j, double e, Mat2X& x, Mat2X& v) const;
  void accumulated(double h, Mat2X& x, Mat2X& v) const;
  void push_apart(Mat2X& x) const;
  ForceWorld forces_;
  VecX m_, r_;
  mutable VecX r_grown_;    // radii plus the contact margin of this step
  mutable Mat2X x_scaled_;  // positions / 8, when their span overflows
  mutable VecX r_scaled_;   // r_grown_ / 8, then
  std::vector<PlaneDef> planes_;
  ContactSettings settings_;
  bool any_radius_ = false;
  std::vector<std::string> initial_notes_;
  Vec2 up_ = Vec2::Zero();  // against the scene's uniform gravity (0 without one)
  bool timing_ = false;
  mutable PhaseTimes times_;
  mutable WorkMeter pairs_;  // the broad phase's candidate pairs, step by step
  mutable Mat2X x_prev_;     // positions after the previous step (continuous check)
  mutable Pairs candidates_, contacts_, sorted_;
  mutable std::vector<std::pair<double, int>> order_;  // (height, contact) for shock_pass
  // The accumulated solver: this step's contacts, and every contact's totals (Pn, Pt)
  // from the last step by key (a, b or plane), for warm starting.
  VecX w_;  // inverse masses
  mutable std::vector<Contact> solved_;
  mutable std::vector<std::uint64_t> keys_;
  mutable std::vector<double> restitution_;
  mutable std::vector<int> plane_;      // the plane of each contact, -1 for a pair
  mutable std::vector<char> impacted_;  // the contact got an impact's impulse this step
  mutable std::unordered_map<std::uint64_t, std::pair<double, double>> kept_, next_;
  // Approaching contacts seen, and those the student's function answered
  // with an impulse: planes (C1), pairs (C2), sliding with friction (C4), the
  // accumulated solver (C5).
  struct Answered {
    long seen = 0, answered = 0;
  };
  mutable Answered plane_hits_, pair_hits_, friction_hits_, solver_hits_;  // C5 too
};

// Makes the lab run its scenes with the forces lab's forces, plus collisions
// in scenes that declare "planes" or "contact"; adds the keys to --help.
void use_collisions(LabInfo& info);

}  // namespace wb
