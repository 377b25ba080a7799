// Loading particle scenes: explicit particles first, then each emitter's.
#include "wb/scene.h"

#include <cmath>
#include <filesystem>
#include <random>

#include "wb/output.h"

namespace wb {

namespace {

const Range kPositive{0.0, std::numeric_limits<double>::infinity(), true};
const Range kNonNegative{0.0};

// A mass m > 0 whose inverse is finite (1/5e-324 overflows).
double read_mass(const JsonObject& o) {
  const double m = o.number("m", kPositive);
  if (!std::isfinite(1.0 / m)) {
    o.fail("m", &o.raw().at("m"), "a mass whose inverse 1/m is finite (m >= 5.6e-309)");
  }
  return m;
}

// Kinetic energy 1/2 m |v|^2 and momentum m |v| both finite.
bool finite_motion(double m, double speed2) {
  return std::isfinite(0.5 * m * speed2) && std::isfinite(m * std::sqrt(speed2));
}

std::string motion_text(double m) {
  std::string s =
      "a velocity whose kinetic energy 1/2 m |v|^2 and momentum m |v| are finite "
      "for m = ";
  append_number(s, m);
  return s;
}

// How many particles the scene declares, checked against kMaxParticles before
// any is built.
Eigen::Index count_particles(const JsonObject& top) {
  std::int64_t n = std::int64_t(top.array_or_empty("particles").size());
  const auto too_many = [&](const std::string& where, const std::string& got) {
    throw InputError(top.file() + ": " + where + ": got " + got + ", expected at most " +
                     std::to_string(kMaxParticles) + " particles in a scene (docs/scenes.md)");
  };
  if (n > kMaxParticles) too_many("particles", std::to_string(n) + " particles");
  const json& list = top.array_or_empty("emitters");
  for (std::size_t k = 0; k < list.size(); ++k) {
    JsonObject e = top.element("emitters", k);
    const std::int64_t count = e.integer("count", 0, kMaxParticles);
    if (count > kMaxParticles - n) {
      too_many(e.key_path("count"), std::to_string(count) + ", which makes " +
                                        std::to_string(n + count) + " particles");
    }
    n += count;
  }
  return Eigen::Index(n);
}

void read_particles(const JsonObject& top, Scene& s, Eigen::Index& next) {
  const json& list = top.array_or_empty("particles");
  for (std::size_t i = 0; i < list.size(); ++i) {
    JsonObject p = top.element("particles", i);
    p.only_keys({"x", "v", "m", "radius"});
    const Vec2 x = p.vec2("x"), v = p.vec2_or("v", Vec2::Zero());
    const double m = read_mass(p);
    if (!finite_motion(m, v.squaredNorm())) p.fail("v", &p.raw().at("v"), motion_text(m));
    s.x.col(next) = x;
    s.v.col(next) = v;
    s.m[next] = m;
    s.radius[next] = p.number_or("radius", 0.0, kNonNegative);
    ++next;
  }
}

void read_emitters(const JsonObject& top, std::optional<std::uint64_t> seed, Scene& s,
                   Eigen::Index& next) {
  const json& list = top.array_or_empty("emitters");
  for (std::size_t k = 0; k < list.size(); ++k) {
    JsonObject e = top.element("emitters", k);
    e.only_keys({"count", "seed", "min", "max", "speed", "m", "radius"});
    const std::int64_t count = e.integer("count", 0, kMaxParticles);
    const std::uint64_t sd =
        seed ? *seed + k : std::uint64_t(e.integer_or("seed", 0, 0, INT64_MAX));
    const Vec2 lo = e.vec2("min"), hi = e.vec2("max");
    for (int d = 0; d < 2; ++d) {
      if (!(hi[d] >= lo[d])) {
        e.fail("max", &e.raw().at("max"), "max >= min in each coordinate");
      }
    }
    // Every position lo + (hi - lo) u, u in [0, 1), lies in the box when the
    // box's size is finite.
    const Vec2 size = hi - lo;
    if (!size.allFinite()) {
      e.fail("max", &e.raw().at("max"),
             "a box whose size max - min is finite in each coordinate (it overflows)");
    }
    const double speed = e.number_or("speed", 0.0, kNonNegative);
    const double m = read_mass(e);
    if (!finite_motion(m, speed * speed)) e.fail("speed", &e.raw().at("speed"), motion_text(m));
    const double r = e.number_or("radius", 0.0, kNonNegative);
    // mt19937_64's sequence is fixed by the standard; the mapping to doubles
    // is ours, so the same seed gives the same particles everywhere.
    std::mt19937_64 rng(sd);
    for (std::int64_t i = 0; i < count; ++i) {
      Vec2 u(unit_double(rng()), unit_double(rng()));
      double angle = 2.0 * M_PI * unit_double(rng());
      s.x.col(next) = lo + size.cwiseProduct(u);
      // + 0.0 turns a -0 (speed 0 times a negative cosine) into 0 in the trace.
      s.v.col(next) = speed * Vec2(std::cos(angle), std::sin(angle)) + Vec2::Zero();
      s.m[next] = m;
      s.radius[next] = r;
      ++next;
    }
  }
}

}  // namespace

Scene scene_from_json(const std::string& file, json doc, std::optional<std::uint64_t> seed,
                      const std::vector<std::string>& extra_keys) {
  Scene s;
  s.file = file;
  s.doc = std::move(doc);
  JsonObject top(file, s.doc, "");
  for (auto it = s.doc.begin(); it != s.doc.end(); ++it) {
    static const char* base[] = {"name",      "dt",       "t_end",  "integrator",
                                 "particles", "emitters", "forces", "description"};
    bool ok = false;
    for (const char* k : base) ok = ok || it.key() == k;
    for (const auto& k : extra_keys) ok = ok || it.key() == k;
    if (!ok) {
      std::string list;
      for (const char* k : base) list += (list.empty() ? "" : ", ") + std::string(k);
      for (const auto& k : extra_keys) list += ", " + k;
      throw InputError(file + ": " + it.key() + ": unknown key, expected one of: " + list);
    }
  }
  s.name = top.string_or("name", std::filesystem::path(file).stem().string());
  if (top.has("description")) top.string("description");
  if (top.has("dt")) s.dt = top.number("dt", kPositive);
  if (top.has("t_end")) s.t_end = top.number("t_end", kNonNegative);
  if (top.has("integrator")) s.integrator = top.string("integrator");
  top.array_or_empty("forces");  // type-checked here, read by the lab

  const Eigen::Index n = count_particles(top);
  s.x.resize(2, n);
  s.v.resize(2, n);
  s.m.resize(n);
  s.radius.resize(n);
  Eigen::Index next = 0;
  read_particles(top, s, next);
  read_emitters(top, seed, s, next);
  return s;
}

Scene load_scene(const std::string& file, std::optional<std::uint64_t> seed,
                 const std::vector<std::string>& extra_keys) {
  return scene_from_json(file, read_json_file(file), seed, extra_keys);
}

std::string particle_key(const Scene& s, Eigen::Index i) {
  const json* p = s.doc.contains("particles") ? &s.doc.at("particles") : nullptr;
  Eigen::Index first = p && p->is_array() ? Eigen::Index(p->size()) : 0;
  if (i < first) return "particles[" + std::to_string(i) + "]";
  const json* e = s.doc.contains("emitters") ? &s.doc.at("emitters") : nullptr;
  for (std::size_t k = 0; e && e->is_array() && k < e->size(); ++k) {
    const json& c = (*e)[k].is_object() ? (*e)[k].value("count", json()) : json();
    first += c.is_number_integer() ? Eigen::Index(c.get<std::int64_t>()) : 0;
    if (i < first) return "emitters[" + std::to_string(k) + "]";
  }
  return "particle " + std::to_string(i) + " (made by the scene's generators)";
}

void check_particles(const Scene& s, const std::string& what) {
  for (Eigen::Index i = 0; i < s.n(); ++i) {
    const double m = s.m[i];
    std::string problem;
    if (!s.x.col(i).allFinite()) {
      problem = "a non-finite position";
    } else if (!s.v.col(i).allFinite()) {
      problem = "a non-finite velocity";
    } else if (!(m > 0.0 && std::isfinite(m) && std::isfinite(1.0 / m))) {
      problem = "mass ";
      append_number(problem, m);
      problem += ", not > 0 with a finite inverse";
    } else if (!finite_motion(m, s.v.col(i).squaredNorm())) {
      problem = "a kinetic energy or momentum that overflows";
    } else if (!(s.radius[i] >= 0.0 && std::isfinite(s.radius[i]))) {
      problem = "a radius that is not a finite number >= 0";
    }
    if (!problem.empty()) {
      throw InputError(s.file + ": particle " + std::to_string(i) + " (made by " + what +
                       ") has " + problem + ", expected a finite state");
    }
  }
}

}  // namespace wb
