// A particle scene: the particles it declares or emits and its raw force list.
// Every key is documented in docs/scenes.md.
#pragma once
#include <any>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "wb/input.h"
#include "wb/types.h"

namespace wb {

struct Scene {
  std::string file;                       // path it was read from
  std::string name;                       // "name" key, or the file's stem
  std::optional<double> dt, t_end;        // scene defaults, flags override
  std::optional<std::string> integrator;  // scene default, --integrator overrides
  Mat2X x, v;                             // positions and velocities (2 x n)
  VecX m;                                 // masses (n), all > 0
  VecX radius;                            // radii (n), all >= 0
  json doc;                               // the whole document (forces and lab keys)
  // What a lab's scene generators built besides particles (LabInfo::expand_scene)
  // for its make_world to read: the implicit lab's rope and cloth springs and pins.
  std::any generated;
  std::int64_t n() const { return x.cols(); }
};

// The most particles a scene may declare (particles plus every emitter's
// count), checked before any is built: about 200 bytes each in a run, 2 GB.
constexpr std::int64_t kMaxParticles = 10'000'000;

// Reads and checks a scene. `seed` (from --seed) replaces emitter k's seed by
// seed + k (mod 2^64). `extra_keys` are top-level keys a lab adds (read by the
// lab). Finite input that would make a non-finite state is refused: a mass
// whose inverse overflows, a kinetic energy or momentum that overflows, an
// emitter box whose size overflows.
Scene load_scene(const std::string& file, std::optional<std::uint64_t> seed,
                 const std::vector<std::string>& extra_keys = {});

// load_scene on a parsed document (`file` names it in messages).
Scene scene_from_json(const std::string& file, json doc, std::optional<std::uint64_t> seed,
                      const std::vector<std::string>& extra_keys = {});

// Checks every particle's state as load_scene does (finite x and v, m > 0
// with a finite 1/m, finite kinetic energy and momentum, radius >= 0), e.g.
// after a lab's scene generators added particles; InputError names the
// particle and `what` made it.
void check_particles(const Scene& scene, const std::string& what);

// The scene entry particle i came from, for messages: "particles[3]",
// "emitters[1]", or "particle 70 (made by the scene's generators)".
std::string particle_key(const Scene& scene, Eigen::Index i);

// A deterministic uniform double in [0, 1) from a 64-bit draw.
inline double unit_double(std::uint64_t r) { return double(r >> 11) * 0x1.0p-53; }

}  // namespace wb
