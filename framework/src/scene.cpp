// Loading particle scenes: explicit particles first, then each emitter's.
#include "wb/scene.h"

#include <cmath>
#include <filesystem>
#include <random>

namespace wb {

namespace {

struct Builder {
  std::vector<Vec2> x, v;
  std::vector<double> m, r;
  void add(const Vec2& xi, const Vec2& vi, double mi, double ri) {
    x.push_back(xi);
    v.push_back(vi);
    m.push_back(mi);
    r.push_back(ri);
  }
};

const Range kPositive{0.0, std::numeric_limits<double>::infinity(), true};
const Range kNonNegative{0.0};
constexpr std::int64_t kMaxParticles = 50'000'000;

void read_particles(const JsonObject& top, Builder& b) {
  const json& list = top.array_or_empty("particles");
  for (std::size_t i = 0; i < list.size(); ++i) {
    JsonObject p = top.element("particles", i);
    p.only_keys({"x", "v", "m", "radius"});
    b.add(p.vec2("x"), p.vec2_or("v", Vec2::Zero()), p.number("m", kPositive),
          p.number_or("radius", 0.0, kNonNegative));
  }
}

void read_emitters(const JsonObject& top, std::optional<std::uint64_t> seed, Builder& b) {
  const json& list = top.array_or_empty("emitters");
  for (std::size_t k = 0; k < list.size(); ++k) {
    JsonObject e = top.element("emitters", k);
    e.only_keys({"count", "seed", "min", "max", "speed", "m", "radius"});
    std::int64_t count = e.integer("count", 0, kMaxParticles);
    std::uint64_t s = seed ? *seed + k : std::uint64_t(e.integer_or("seed", 0, 0, INT64_MAX));
    Vec2 lo = e.vec2("min"), hi = e.vec2("max");
    for (int d = 0; d < 2; ++d) {
      if (!(hi[d] >= lo[d])) {
        e.fail("max", &e.raw().at("max"), "max >= min in each coordinate");
      }
    }
    double speed = e.number_or("speed", 0.0, kNonNegative);
    double m = e.number("m", kPositive);
    double r = e.number_or("radius", 0.0, kNonNegative);
    // mt19937_64's sequence is fixed by the standard; the mapping to doubles
    // is ours, so the same seed gives the same particles everywhere.
    std::mt19937_64 rng(s);
    for (std::int64_t i = 0; i < count; ++i) {
      Vec2 u(unit_double(rng()), unit_double(rng()));
      double angle = 2.0 * M_PI * unit_double(rng());
      // + 0.0 turns a -0 (speed 0 times a negative cosine) into 0 in the trace.
      b.add(lo + (hi - lo).cwiseProduct(u),
            speed * Vec2(std::cos(angle), std::sin(angle)) + Vec2::Zero(), m, r);
    }
  }
}

}  // namespace

Scene load_scene(const std::string& file, std::optional<std::uint64_t> seed,
                 const std::vector<std::string>& extra_keys) {
  Scene s;
  s.file = file;
  s.doc = read_json_file(file);
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

  Builder b;
  read_particles(top, b);
  read_emitters(top, seed, b);
  if (b.x.size() > std::size_t(kMaxParticles)) {
    throw InputError(file + ": particles + emitters: " + std::to_string(b.x.size()) +
                     " particles, expected at most " + std::to_string(kMaxParticles));
  }
  const Eigen::Index n = Eigen::Index(b.x.size());
  s.x.resize(2, n);
  s.v.resize(2, n);
  s.m.resize(n);
  s.radius.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    s.x.col(i) = b.x[i];
    s.v.col(i) = b.v[i];
    s.m[i] = b.m[i];
    s.radius[i] = b.r[i];
  }
  return s;
}

}  // namespace wb
