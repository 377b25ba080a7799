#include "apply_force.h"

// TODO(R3) add a force at a point, and gravity (see apply_force.h).
// Plan: 1. apply_force: add F to b.f and the torque (p - x) x F to b.tau;
//       2. apply_gravity: add m g to b.f only.
void apply_force(rigid::Body& b, const rigid::Vec3& F, const rigid::Vec3& p) {
  // ---- Replace with your code ----
  (void)b, (void)F, (void)p;
  // ---- end ----
}

void apply_gravity(rigid::Body& b, const rigid::Vec3& g) {
  // ---- Replace with your code ----
  (void)b, (void)g;
  // ---- end ----
}
