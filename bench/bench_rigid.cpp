// Rigid lab throughput: one body's step with the gyroscopic term taken
// explicitly or implicitly (one 3x3 Newton solve), and the pieces around it,
// against a baseline measured in the same run: the position update alone
// (x += h v and one quaternion product). bench/summarize.py-style ratios are
// stated in docs/benchmarks.md ("rigid"): time / time of position_only.
//
//   position_only        integrate_position (R4): the baseline
//   velocity_explicit    integrate_velocity_explicit (R5) + R4
//   velocity_implicit    integrate_velocity_implicit (R5) + R4
//   box_on_floor         the glue's whole step of a box resting on a plane:
//                        gravity, implicit velocity, 8 corners of contact, R4
#include <benchmark/benchmark.h>

#include "integrate_position.h"
#include "integrate_velocity.h"
#include "rigid_world.h"

namespace {

rigid::Body tumbling() {
  rigid::Body b;
  b.m = 2.0;
  b.I_body = rigid::Vec3(1.0, 2.0, 3.0).asDiagonal();
  b.q = Eigen::Quaterniond(0.7, 0.1, -0.4, 0.3).normalized();
  b.omega = rigid::Vec3(1.0, -0.5, 2.0);
  return b;
}

constexpr double kH = 1e-4;  // small: the body stays in the same regime for the whole run

void position_only(benchmark::State& state) {
  rigid::Body b = tumbling();
  for (auto _ : state) {
    integrate_position(b, kH);
    benchmark::DoNotOptimize(b);
  }
}

void velocity_explicit(benchmark::State& state) {
  rigid::Body b = tumbling();
  for (auto _ : state) {
    integrate_velocity_explicit(b, kH);
    integrate_position(b, kH);
    benchmark::DoNotOptimize(b);
  }
}

void velocity_implicit(benchmark::State& state) {
  rigid::Body b = tumbling();
  for (auto _ : state) {
    integrate_velocity_implicit(b, kH);
    integrate_position(b, kH);
    benchmark::DoNotOptimize(b);
  }
}

void box_on_floor(benchmark::State& state) {
  rigid::Scene scene;
  rigid::BodyDef def;
  def.size = rigid::Vec3(1.0, 2.0, 0.5);
  def.body.m = 2.0;
  def.body.I_body = rigid::Vec3(0.708, 0.208, 0.833).asDiagonal();
  def.body.x = rigid::Vec3(0, 0, 0.25);
  scene.bodies.push_back(def);
  scene.g = rigid::Vec3(0, 0, -9.81);
  scene.planes.push_back({});
  const rigid::Integrator integ{"implicit-gyroscopic", integrate_velocity_implicit, ""};
  std::vector<rigid::Body> bodies{def.body};
  for (auto _ : state) {
    rigid::step(scene, integ, 1e-3, bodies);
    benchmark::DoNotOptimize(bodies.data());
  }
}

}  // namespace

BENCHMARK(position_only);
BENCHMARK(velocity_explicit);
BENCHMARK(velocity_implicit);
BENCHMARK(box_on_floor);
BENCHMARK_MAIN();
