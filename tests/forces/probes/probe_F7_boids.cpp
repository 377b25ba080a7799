// Diagnosis probes of F7 (tests/common/wb_probe.h): each rule alone (details), a boid with no
// neighbours, rules of different radii, the goal, the masses, coincident boids, a flock with
// everything. In the probes of one rule the last boid sits where that rule gives it no steering
// (the midpoint of the other two, moving with their mean velocity): a loop that skips the last
// boid does not show there. Wherever a boid lies beyond a radius, the rules' radii differ, so
// that a rule that takes another's radius shows wherever one that takes none does; the probes
// where a mean is taken have a boid with no neighbour and one with some but not all.
#include "boids.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_F7_boids {

using wbprobe::cols;
using wbprobe::vec;

namespace {
using wb::Mat2X;
using wb::VecX;

BoidsParams rules(double ws, double wa, double wc, double radius) {
  BoidsParams p;
  p.separation = {ws, radius};
  p.alignment = {wa, radius};
  p.cohesion = {wc, radius};
  return p;
}

void run(wbprobe::Probe& P, const Mat2X& x, const Mat2X& v, const VecX& m, const BoidsParams& p,
         Mat2X f, bool each = false) {
  P.call("add_boids");
  P.in("x", x), P.in("v", v), P.in("m", m);
  P.in("separation.weight", p.separation.weight), P.in("separation.radius", p.separation.radius);
  P.in("alignment.weight", p.alignment.weight), P.in("alignment.radius", p.alignment.radius);
  P.in("cohesion.weight", p.cohesion.weight), P.in("cohesion.radius", p.cohesion.radius);
  P.in("goal_weight", p.goal_weight), P.in("goal", p.goal), P.in("f", f);
  add_boids(x, v, m, p, f);
  if (each) {
    P.out_each("f", f);
  } else {
    P.out("f", f);
  }
}
Mat2X zeros(Eigen::Index n) { return Mat2X::Zero(2, n); }
// Two boids and their midpoint last.
const Mat2X kTrio = cols({{0.4, 0.7}, {1.6, 1.3}, {1, 1}});
}  // namespace

WB_PROBE("F7", "separation-two", "separation alone: two boids 0.5 apart, every radius 1") {
  P.simple();
  run(P, cols({{0, 0}, {0.5, 0}}), zeros(2), vec({1, 1}), rules(1, 0, 0, 1), zeros(2));
}
// One rule at a time.
// Cohesion's radius (7, its weight 0) reaches every boid: a separation that takes another rule's
// radius, or none, shows here.
WB_PROBE("F7", "separation",
         "separation alone, radius 2 (cohesion's 7, weight 0): two boids and their midpoint "
         "(last); far away, two boids at one point and a third 0.5 from them") {
  BoidsParams p = rules(0.7, 0, 0, 2);
  p.cohesion.radius = 7;
  run(P, cols({{0.4, 0.7}, {1.6, 1.3}, {5, 5}, {5, 5}, {5.5, 5}, {1, 1}}), zeros(6),
      vec({1, 1, 1, 1, 1, 1}), p, zeros(6), true);
}
WB_PROBE("F7", "alignment", "alignment alone: two boids and their midpoint, moving differently") {
  P.simple();
  run(P, kTrio, cols({{1, 0}, {-0.2, 0.8}, {0.4, 0.4}}), vec({1, 1, 1}), rules(0, 0.9, 0, 2),
      zeros(3));
}
WB_PROBE("F7", "cohesion", "cohesion alone: two boids and their midpoint") {
  P.simple();
  run(P, kTrio, zeros(3), vec({1, 1, 1}), rules(0, 0, 0.6, 2), zeros(3));
}
// Who counts in a mean, in the cohesion and then in the alignment (a mistake in how one rule
// steers towards its mean shows in one of the two, a mistake in the means in both): three boids
// near each other, one alone (last). Separation's radius 0.9 reaches no pair: a separation of
// another rule's radius shows, a separation formula does not.
WB_PROBE("F7", "means",
         "cohesion, radius 2.5, and separation, radius 0.9: two neighbours of the first boid 1 "
         "and 1.2 from it, one boid far from all") {
  BoidsParams p = rules(0.7, 0, 0.6, 2.5);
  p.separation.radius = 0.9;
  run(P, cols({{0, 0}, {1, 0}, {0, 1.2}, {5, 5}}), cols({{1, 0}, {0, 1}, {-1, 0.5}, {0.3, 0.3}}),
      vec({1, 1, 1, 1}), p, zeros(4));
}
WB_PROBE("F7", "means-align",
         "alignment, radius 2.5, and separation, radius 0.9: two neighbours of the first boid 1 "
         "and 1.2 from it, one boid far from all") {
  BoidsParams p = rules(0.7, 0.9, 0, 2.5);
  p.separation.radius = 0.9;
  run(P, cols({{0, 0}, {1, 0}, {0, 1.2}, {5, 5}}), cols({{1, 0}, {0, 1}, {-1, 0.5}, {0.3, 0.3}}),
      vec({1, 1, 1, 1}), p, zeros(4));
}
// Each rule its own radius; a boid far from all last (no neighbour: nothing).
WB_PROBE("F7", "radii",
         "every rule on, radii 0.9, 1.6 and 2.6: boids 0.8 and 2.06 from the first, one far from "
         "all") {
  BoidsParams p = rules(0.7, 0.9, 0.6, 0.9);
  p.alignment.radius = 1.6, p.cohesion.radius = 2.6;
  run(P, cols({{0, 0}, {0.8, 0}, {2, 0.5}, {8, -8}}), cols({{0, 0}, {1, 0}, {0, 1}, {0.5, 0.5}}),
      vec({1, 1, 1, 1}), p, zeros(4));
}
// The goal: a boid 5 from it and one on it (last).
WB_PROBE("F7", "goal", "the goal alone: a boid 5 from its goal, another standing on it") {
  BoidsParams p = rules(0, 0, 0, 10);
  p.goal_weight = 1.3, p.goal = wb::Vec2(1, -1);
  run(P, cols({{4, 3}, {1, -1}}), zeros(2), vec({1, 1}), p, zeros(2));
}
// The masses.
WB_PROBE("F7", "masses", "separation alone, masses 2 and 0.5, and their midpoint") {
  P.simple();
  run(P, kTrio, zeros(3), vec({2, 0.5, 3}), rules(0.7, 0, 0, 2), zeros(3));
}
// Coincident boids.
WB_PROBE("F7", "coincident", "two boids at the same point and a third 0.5 away, every rule on") {
  P.simple();
  run(P, cols({{0, 0}, {0, 0}, {0.5, 0}}), cols({{1, 0}, {0, 1}, {0, 0}}), vec({1, 1, 1}),
      rules(0.7, 0.9, 0.6, 2), zeros(3));
}
// Every rule, different radii and masses, f holding forces; a boid far from all last.
WB_PROBE("F7", "flock", "four boids, every rule, f holding forces, and a boid far from all") {
  BoidsParams p = rules(0.5, 0.8, 0.3, 1.2);
  p.alignment.radius = 2, p.cohesion.radius = 2.5;
  run(P, cols({{0, 0}, {0.7, 0.2}, {1.5, -0.5}, {-0.9, 1.1}, {9, 9}}),
      cols({{1, 0}, {0.5, 0.5}, {0, -1}, {-0.3, 0.2}, {0.2, 0.1}}), vec({1, 2, 0.5, 1.5, 1}), p,
      cols({{1, 0}, {0, 1}, {-1, 0}, {0.5, 0.5}, {0, 0}}));
}
// Every boid: all within every radius, so that only the boid a loop misses goes wrong alone;
// separation alone (who counts in a mean shows in "means", not here).
WB_PROBE("F7", "every",
         "four boids all within every radius (3), separation alone, masses 1, 2, 0.5 and 1.5") {
  run(P, cols({{0, 0}, {0.7, 0.2}, {1.5, -0.5}, {-0.9, 1.1}}),
      cols({{1, 0}, {0.5, 0.5}, {0, -1}, {-0.3, 0.2}}), vec({1, 2, 0.5, 1.5}),
      rules(0.5, 0, 0, 3), zeros(4), true);
}

}  // namespace probe_F7_boids
