// The elastic gas of issue 34, a scene built in code: 150 discs of 1 kg at 2 m/s and 150 of
// 4 kg at 1 m/s (600 J), radius 5 cm, from two seeded emitters uniform in a 3.8 m square,
// inside a 4 m box of elastic walls; about 90 pairs overlap at t = 0. One scene for the
// physics test that it keeps its energy (test_collisions_energy.cpp) and the benchmark that
// times it (bench/bench_collisions.cpp, BM_gas).
#pragma once
#include "wb/scene.h"

namespace wbgas {

// The scene's JSON (dt 1 ms, t_end 0.5 s) with the given "contact" block.
inline wb::json elastic_gas(const wb::json& contact) {
  wb::json doc = {{"dt", 0.001}, {"t_end", 0.5}};
  doc["emitters"] = {{{"count", 150},
                      {"seed", 1},
                      {"min", {-1.9, -1.9}},
                      {"max", {1.9, 1.9}},
                      {"speed", 2.0},
                      {"m", 1.0},
                      {"radius", 0.05}},
                     {{"count", 150},
                      {"seed", 2},
                      {"min", {-1.9, -1.9}},
                      {"max", {1.9, 1.9}},
                      {"speed", 1.0},
                      {"m", 4.0},
                      {"radius", 0.05}}};
  doc["planes"] = {{{"point", {-2, 0}}, {"normal", {1, 0}}},
                   {{"point", {2, 0}}, {"normal", {-1, 0}}},
                   {{"point", {0, -2}}, {"normal", {0, 1}}},
                   {{"point", {0, 2}}, {"normal", {0, -1}}}};
  doc["contact"] = contact;
  return doc;
}

}  // namespace wbgas
