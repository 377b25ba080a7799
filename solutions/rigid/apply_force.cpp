#include "apply_force.h"

// TODO(R3) add a force at a point, and gravity (see apply_force.h).
void apply_force(rigid::Body& b, const rigid::Vec3& F, const rigid::Vec3& p) {
  b.f += F;
  b.tau += (p - b.x).cross(F);
}

void apply_gravity(rigid::Body& b, const rigid::Vec3& g) { b.f += b.m * g; }
