// How many particles a scene document asks for, counted cheaply before it is
// loaded: the particle targets skip an input above their own limit, as the
// loader's and the step's cost grow with it (fuzz/README.md).
#pragma once
#include "wb/input.h"
#include "wb/scene.h"

namespace fuzzcheck {

// A number at `key` of object `o` in (0, kMaxParticles], else 0.
inline double small_count(const wb::json& o, const char* key) {
  if (!o.is_object()) return 0;
  auto it = o.find(key);
  if (it == o.end() || !it->is_number()) return 0;
  const double v = it->get<double>();
  return v > 0 && v <= double(wb::kMaxParticles) ? v : 0;
}

// Its particles, its emitters' counts, and what a rope or a cloth (the implicit
// lab's generators) would add.
inline double declared_particles(const wb::json& doc) {
  if (!doc.is_object()) return 0;
  double n = 0;
  auto p = doc.find("particles");
  if (p != doc.end() && p->is_array()) n += double(p->size());
  auto e = doc.find("emitters");
  if (e != doc.end() && e->is_array())
    for (const auto& em : *e) n += small_count(em, "count");
  auto r = doc.find("rope");
  if (r != doc.end()) n += small_count(*r, "beads");
  auto c = doc.find("cloth");
  if (c != doc.end()) n += small_count(*c, "rows") * small_count(*c, "cols");
  return n;
}

}  // namespace fuzzcheck
