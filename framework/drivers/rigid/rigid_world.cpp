// The rigid lab's scene keys and step (docs/scenes.md, "rigid").
#include "rigid_world.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "apply_force.h"
#include "body_inertia.h"
#include "hinge.h"
#include "integrate_position.h"
#include "plane_contact.h"
#include "wb/budget.h"
#include "wb/run.h"

namespace rigid {

namespace {

using wb::json;
using wb::JsonObject;

// An array of n finite numbers at `key`.
Eigen::VectorXd read_numbers(const JsonObject& o, const char* key, int n) {
  const std::string expected = "an array of " + std::to_string(n) + " finite numbers";
  if (!o.has(key)) o.fail(key, nullptr, expected);
  const wb::json& v = o.raw().at(key);
  if (!v.is_array() || int(v.size()) != n) o.fail(key, &v, expected);
  Eigen::VectorXd out(n);
  for (int i = 0; i < n; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) {
      o.fail(std::string(key) + "[" + std::to_string(i) + "]", &v[i], "a finite number");
    }
    out[i] = v[i].get<double>();
  }
  return out;
}

Vec3 vec3(const JsonObject& o, const char* key) { return read_numbers(o, key, 3); }
Vec3 vec3_or(const JsonObject& o, const char* key, const Vec3& def) {
  return o.has(key) ? vec3(o, key) : def;
}

// A unit direction: non-zero, normalised. Scaled by its largest component
// first, so that [1e200, 1e200, 0] (whose norm overflows) and [1e-200, 0, 0]
// (whose squared norm underflows) give a unit vector, not a zero one.
Vec3 direction(const JsonObject& o, const char* key) {
  const Vec3 d = vec3(o, key);
  const double scale = d.cwiseAbs().maxCoeff();
  if (!(scale > 0)) o.fail(key, &o.raw().at(key), "a non-zero vector");
  return (d / scale).normalized();
}

// [w, x, y, z], non-zero, normalised on load.
Eigen::Quaterniond quaternion_or(const JsonObject& o, const char* key) {
  if (!o.has(key)) return Eigen::Quaterniond::Identity();
  const Eigen::VectorXd a = read_numbers(o, key, 4);
  Eigen::Quaterniond q(a[0], a[1], a[2], a[3]);
  if (!(q.norm() > 1e-12) || !std::isfinite(q.norm())) {
    o.fail(key, &o.raw().at(key), "a non-zero quaternion [w, x, y, z]");
  }
  q.normalize();
  return q;
}

int body_index(const JsonObject& o, const Scene& s) {
  return int(o.integer("body", 0, std::int64_t(s.bodies.size()) - 1));
}

// The bounds on a body's initial numbers (docs/scenes.md, "rigid"). They use
// the scene's own numbers (m and the dimensions), never the inertia of the
// student's R1 functions, so that the skeleton loads the scenes the solution
// loads.
//
// Inertia scale: every principal moment of inertia of a uniform box, sphere
// or cylinder lies between m d_min^2 / 6 and m d_max^2 / 2, d_min and d_max its
// smallest and largest dimension (box edges; sphere radius; cylinder radius
// and length). Keeping m d^2 within [1e-290, 1e290] for both keeps every
// moment and its inverse finite, with about 18 orders of magnitude to spare
// for the products a step forms (I omega, R I R^T, the hinge's and contacts'
// effective masses). The product is formed as m (d d), as the inertia
// formulas form it, so a d d that underflows to 0 is refused rather than
// accepted with I = 0.
constexpr double kMinInertiaScale = 1e-290;
constexpr double kMaxInertiaScale = 1e290;
// Every initial quantity of one body (its kinetic and potential energy, the
// largest component of its momentum and angular momentum) is at most this, so
// that the totals, sums over the bodies of a file of at most 16 MiB (fewer
// than 10^6 bodies), stay finite with a margin of 10^2.
constexpr double kMaxBodyQuantity = 1e300;
// The limits as the messages write them (wb::num writes 1e-290 with 17 digits).
constexpr const char* kInertiaScaleText = "from 1e-290 to 1e+290";
constexpr const char* kMaxBodyQuantityText = "1e+300";
// A hinge's anchor and its body's centre at most this many body sizes from the
// origin (check_hinge).
constexpr double kMaxHingeReach = 0x1p42;

bool inertia_scale_ok(double m, double d) {
  const double s = m * (d * d);
  return s >= kMinInertiaScale && s <= kMaxInertiaScale;
}

std::string inertia_expected(double m) {
  return std::string("lengths d with m d^2 ") + kInertiaScaleText + " for m = " + wb::num(m) +
         " (the inertia, about m d^2, and its inverse must be finite)";
}

// An upper bound of every principal moment of inertia of the body: m d_max^2
// (the largest moment is m (b^2 + c^2) / 12 for a box, 2/5 m r^2 for a sphere,
// m (3 r^2 + L^2) / 12 or m r^2 / 2 for a cylinder).
double inertia_bound(const BodyDef& d) {
  double dmax = d.radius;
  if (d.shape == BodyDef::kBox) dmax = d.size.maxCoeff();
  if (d.shape == BodyDef::kCylinder) dmax = std::max(d.radius, d.length);
  return d.body.m * (dmax * dmax);
}

bool within_body_limit(double q) { return std::abs(q) <= kMaxBodyQuantity; }

const json* value_at(const JsonObject& o, const char* key) {
  return o.has(key) ? &o.raw().at(key) : nullptr;
}

BodyDef read_body(const JsonObject& o) {
  BodyDef d;
  const std::string shape = o.string("shape");
  const wb::Range positive{0, std::numeric_limits<double>::infinity(), true};
  const double m = d.body.m = o.number("m", positive);
  if (!std::isfinite(1.0 / m)) {
    o.fail("m", &o.raw().at("m"), "a mass whose inverse 1/m is finite (m >= 5.6e-309)");
  }
  if (shape == "box") {
    o.only_keys({"shape", "size", "m", "x", "v", "q", "omega"});
    d.shape = BodyDef::kBox;
    d.size = vec3(o, "size");
    if (!(d.size.minCoeff() > 0)) o.fail("size", &o.raw().at("size"), "3 lengths > 0");
    if (!inertia_scale_ok(m, d.size.minCoeff()) || !inertia_scale_ok(m, d.size.maxCoeff())) {
      o.fail("size", &o.raw().at("size"), inertia_expected(m));
    }
    d.body.I_body = box_inertia(m, d.size);
  } else if (shape == "sphere") {
    o.only_keys({"shape", "radius", "m", "x", "v", "q", "omega"});
    d.shape = BodyDef::kSphere;
    d.radius = o.number("radius", positive);
    if (!inertia_scale_ok(m, d.radius))
      o.fail("radius", &o.raw().at("radius"), inertia_expected(m));
    d.body.I_body = sphere_inertia(m, d.radius);
  } else if (shape == "cylinder") {
    o.only_keys({"shape", "radius", "length", "m", "x", "v", "q", "omega"});
    d.shape = BodyDef::kCylinder;
    d.radius = o.number("radius", positive);
    d.length = o.number("length", positive);
    if (!inertia_scale_ok(m, d.radius))
      o.fail("radius", &o.raw().at("radius"), inertia_expected(m));
    if (!inertia_scale_ok(m, d.length))
      o.fail("length", &o.raw().at("length"), inertia_expected(m));
    d.body.I_body = cylinder_inertia(m, d.radius, d.length);
  } else {
    o.fail("shape", &o.raw().at("shape"), "one of: box, sphere, cylinder");
  }
  d.body.x = vec3_or(o, "x", Vec3::Zero());
  d.body.v = vec3_or(o, "v", Vec3::Zero());
  d.body.q = quaternion_or(o, "q");
  d.body.omega = vec3_or(o, "omega", Vec3::Zero());
  // The translational and spin parts of the energy and momenta, formed as
  // rigid::totals forms them (the spin ones with the bound of the inertia).
  const Vec3& v = d.body.v;
  if (!within_body_limit(0.5 * m * v.squaredNorm()) ||
      !within_body_limit((m * v).cwiseAbs().maxCoeff())) {
    o.fail("v", value_at(o, "v"),
           "a velocity whose kinetic energy 1/2 m |v|^2 and momentum m |v| are at most " +
               std::string(kMaxBodyQuantityText) + " for m = " + wb::num(m));
  }
  const double I = inertia_bound(d);
  const Vec3& w = d.body.omega;
  if (!within_body_limit(0.5 * I * w.squaredNorm()) ||
      !within_body_limit(I * w.cwiseAbs().maxCoeff())) {
    o.fail("omega", value_at(o, "omega"),
           "an angular velocity whose kinetic energy 1/2 I |omega|^2 and angular momentum "
           "I |omega| are at most " +
               std::string(kMaxBodyQuantityText) + " for I = m d_max^2 = " + wb::num(I));
  }
  return d;
}

// The terms of the body's potential energy and orbital angular momentum,
// which need the scene's gravity (read after the bodies).
void check_position(const JsonObject& o, const BodyDef& d, const Vec3& g) {
  const Body& b = d.body;
  if (!within_body_limit(b.m * g.dot(b.x)) ||
      !within_body_limit((b.m * b.x.cross(b.v)).cwiseAbs().maxCoeff())) {
    o.fail("x", value_at(o, "x"),
           "a position whose potential energy m |g.x| and angular momentum m |x cross v| are "
           "at most " +
               std::string(kMaxBodyQuantityText) + " for m = " + wb::num(b.m) + ", g = [" +
               wb::num(g.x()) + ", " + wb::num(g.y()) + ", " + wb::num(g.z()) + "]");
  }
}

// The initial totals with every body's inertia replaced by its bound m d_max^2
// (so the student's R1 functions play no part): finite whenever every body's
// terms are within kMaxBodyQuantity, and so are the totals of any inertia
// within that bound. Kept as the last line of defence, as the particle labs'
// wb::check_initial_state.
void check_initial_totals(const Scene& s) {
  std::vector<Body> bodies;
  for (const BodyDef& d : s.bodies) {
    bodies.push_back(d.body);
    bodies.back().I_body = inertia_bound(d) * Mat3::Identity();
  }
  const Totals t = totals(s, bodies);
  if (std::isfinite(t.kinetic) && std::isfinite(t.potential) && std::isfinite(t.energy()) &&
      t.p.allFinite() && t.L.allFinite()) {
    return;
  }
  const auto vec = [](const Vec3& a) {
    return "[" + wb::num(a.x()) + ", " + wb::num(a.y()) + ", " + wb::num(a.z()) + "]";
  };
  throw wb::InputError(s.file + ": initial state: kinetic energy " + wb::num(t.kinetic) +
                       ", potential energy " + wb::num(t.potential) + ", momentum " + vec(t.p) +
                       ", angular momentum " + vec(t.L) +
                       ", expected finite values (a position, velocity, angular velocity, mass "
                       "or size is so large that they overflow)");
}

// A body's smallest and largest dimension (box edges; radius; radius and length).
double smallest_dimension(const BodyDef& d) {
  if (d.shape == BodyDef::kBox) return d.size.minCoeff();
  if (d.shape == BodyDef::kCylinder) return std::min(d.radius, d.length);
  return d.radius;
}
double largest_dimension(const BodyDef& d) {
  if (d.shape == BodyDef::kBox) return d.size.maxCoeff();
  if (d.shape == BodyDef::kCylinder) return std::max(d.radius, d.length);
  return d.radius;
}

// A point force's lever arm: its torque |point| |F| and the angular acceleration
// it gives, |point| |F| / I_min (I_min >= m d_min^2 / 6, the scene's numbers), at
// most kMaxBodyQuantity (largest components).
void check_lever(const JsonObject& o, const char* key, const BodyDef& d, double arm, double F) {
  const double I_min = d.body.m * (smallest_dimension(d) * smallest_dimension(d)) / 6;
  const double torque = arm * F;
  if (within_body_limit(torque) && within_body_limit(torque / I_min)) return;
  o.fail(key, value_at(o, key),
         "a point and a force F whose torque |point| |F| (" + wb::num(torque) +
             " N m) and angular acceleration |point| |F| / I (I >= m d_min^2 / 6 = " +
             wb::num(I_min) + ") are at most " + std::string(kMaxBodyQuantityText));
}

// A hinge's numbers, resolvable: its anchor and the body's centre within
// kMaxHingeReach body sizes of the origin (the drift |x + R r - anchor| is a
// difference of numbers of that size: rounded to 2^-52 of them, it stays 2^-10 of
// the body), and the hinge's effective inverse mass 1/m + |r|^2 / I_min finite.
void check_hinge(const JsonObject& o, const BodyDef& d, const Hinge& hg) {
  const double size = largest_dimension(d);
  const double reach = std::max(hg.anchor.cwiseAbs().maxCoeff(), d.body.x.cwiseAbs().maxCoeff());
  const double I_min = d.body.m * (smallest_dimension(d) * smallest_dimension(d)) / 6;
  const double r = hg.r_body.cwiseAbs().maxCoeff();
  if (reach <= kMaxHingeReach * size && within_body_limit(1 / d.body.m + 3 * (r * r) / I_min)) {
    return;
  }
  o.fail("anchor", &o.raw().at("anchor"),
         "an anchor and a body centre within 2^42 body sizes (" + wb::num(kMaxHingeReach * size) +
             " m) of the origin, so that the hinge's drift is resolvable at the body's scale "
             "(this one reaches " +
             wb::num(reach) + " m)");
}

// The floor of the run's energy scale (docs/run-contract.md, "Diverged"), the work of
// the initial forces across the scene, sum of (m |g| + |F|) times the scene size: a
// number formed from the scene's own, refused when it overflows (a body of 1e308 kg
// under gravity), never turned into a scale of 0 that calls step 1 diverged.
void check_work_scale(const Scene& s) {
  const double w = work_scale_of(s);
  if (std::isfinite(w)) return;
  std::size_t heaviest = 0;
  for (std::size_t i = 0; i < s.bodies.size(); ++i)
    if (s.bodies[i].body.m > s.bodies[heaviest].body.m) heaviest = i;
  throw wb::InputError(
      s.file + ": bodies[" + std::to_string(heaviest) + "].m: got " +
      wb::num(s.bodies[heaviest].body.m) +
      ", expected masses, gravity, forces and positions whose initial work across the scene, "
      "sum of (m |g| + |F|) times the scene's size (the divergence rule's energy scale, "
      "docs/run-contract.md), is finite; it overflows");
}

}  // namespace

double work_scale_of(const Scene& scene) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = -lo;
  double far = 0, force = 0;
  for (const BodyDef& d : scene.bodies) {
    const Body& b = d.body;
    lo = lo.cwiseMin(b.x);
    hi = hi.cwiseMax(b.x);
    far = std::max(far, b.x.norm());
    force += b.m * scene.g.norm();
  }
  for (const PointForce& f : scene.point_forces) force += f.F.norm();
  double S = scene.bodies.empty() ? 0.0 : std::max((hi - lo).norm(), far);
  if (!(std::isfinite(S) && S > 0)) S = 1.0;
  return force * S;
}

std::vector<std::string> initial_overlap_notes(const Scene& s) {
  constexpr double kOverlapTol = 1e-9;  // m: below this, rounding of a body set on the plane
  long count = 0;
  double deepest = 0;
  std::size_t body = 0, plane = 0;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    for (std::size_t k = 0; k < s.planes.size(); ++k) {
      const Plane& pl = s.planes[k];
      double d = 0;
      for (const Vec3& p : contact_points(s.bodies[i], s.bodies[i].body, pl))
        d = std::max(d, (pl.point - p).dot(pl.normal));
      if (!(d > kOverlapTol)) continue;
      ++count;
      if (d > deepest) deepest = d, body = i, plane = k;
    }
  }
  if (count == 0) return {};
  char depth[32];
  std::snprintf(depth, sizeof depth, "%.3g", deepest);
  return {s.file + ": " + std::to_string(count) + (count == 1 ? " overlap" : " overlaps") +
          " of a body with a plane at t = 0, the deepest " + depth + " m (bodies[" +
          std::to_string(body) + "] and planes[" + std::to_string(plane) +
          "]): the contact pushes the bodies out by moving positions only, which adds no kinetic "
          "energy"};
}

Scene load_scene(const std::string& file) {
  return scene_from_json(file, wb::read_json_file(file));
}

Scene scene_from_json(const std::string& file, const wb::json& doc) {
  Scene s;
  s.file = file;
  JsonObject top(file, doc, "");
  top.only_keys({"name", "description", "dt", "t_end", "integrator", "bodies", "forces", "planes",
                 "contact", "hinges"});
  s.name = top.string_or("name", std::filesystem::path(file).stem().string());
  if (top.has("description")) top.string("description");
  const wb::Range positive{0, std::numeric_limits<double>::infinity(), true};
  if (top.has("dt")) s.dt = top.number("dt", positive);
  if (top.has("t_end")) s.t_end = top.number("t_end", {.min = 0});
  if (top.has("integrator")) s.integrator = top.string("integrator");

  const wb::json& bodies = top.array_or_empty("bodies");
  if (bodies.empty())
    top.fail("bodies", top.has("bodies") ? &doc.at("bodies") : nullptr,
             "an array of at least one body");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    s.bodies.push_back(read_body(top.element("bodies", i)));
  }
  const wb::json& forces = top.array_or_empty("forces");
  for (std::size_t i = 0; i < forces.size(); ++i) {
    JsonObject f = top.element("forces", i);
    const std::string type = f.string("type");
    if (type == "gravity") {
      f.only_keys({"type", "g"});
      s.g += vec3(f, "g");
      if (!s.g.allFinite()) {
        f.fail("g", &f.raw().at("g"), "a gravity whose sum with the earlier ones is finite");
      }
    } else if (type == "force") {
      f.only_keys({"type", "body", "point", "F"});
      PointForce pf;
      pf.body = body_index(f, s);
      pf.point_body = vec3_or(f, "point", Vec3::Zero());
      pf.F = vec3(f, "F");
      check_lever(f, "point", s.bodies[pf.body], pf.point_body.cwiseAbs().maxCoeff(),
                  pf.F.cwiseAbs().maxCoeff());
      s.point_forces.push_back(pf);
    } else {
      f.fail("type", &f.raw().at("type"), "one of: gravity, force");
    }
  }
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    check_position(top.element("bodies", i), s.bodies[i], s.g);
  }
  check_initial_totals(s);
  const wb::json& planes = top.array_or_empty("planes");
  double heaviest = 0;
  for (const BodyDef& d : s.bodies) heaviest = std::max(heaviest, d.body.m);
  for (std::size_t i = 0; i < planes.size(); ++i) {
    JsonObject p = top.element("planes", i);
    p.only_keys({"point", "normal"});
    s.planes.push_back({vec3_or(p, "point", Vec3::Zero()), direction(p, "normal")});
    // A body pushed onto the plane has the potential energy of its point: the
    // same bound as a body's own position (check_position), for the heaviest.
    if (!within_body_limit(heaviest * s.g.dot(s.planes.back().point))) {
      p.fail("point", value_at(p, "point"),
             "a point whose potential energy m |g.point| for the heaviest body (m = " +
                 wb::num(heaviest) + ") is at most " + std::string(kMaxBodyQuantityText));
    }
  }
  // A contact's effective inverse mass along its normal, 1/m + |r x n|^2 / I with r up to
  // the body's size from its centre, is what the contact impulses divide by: finite and
  // not so large that its inverse is 0 (a contact that could push nothing).
  for (std::size_t i = 0; i < s.bodies.size() && !s.planes.empty(); ++i) {
    const BodyDef& d = s.bodies[i];
    const double dmin = smallest_dimension(d), dmax = largest_dimension(d);
    const double I_min = d.body.m * (dmin * dmin) / 6;
    const double w = 1 / d.body.m + 3 * (dmax * dmax) / I_min;
    if (within_body_limit(w)) continue;
    JsonObject o = top.element("bodies", i);
    const char* key = d.shape == BodyDef::kBox      ? "size"
                      : d.shape == BodyDef::kSphere ? "radius"
                      : dmax == d.length            ? "length"
                                                    : "radius";
    o.fail(key, &o.raw().at(key),
           "a body whose contacts with the planes can be solved: the effective inverse mass "
           "at its surface, 1/m + 3 d_max^2 / I_min with I_min = m d_min^2 / 6, at most " +
               std::string(kMaxBodyQuantityText) + " (here " + wb::num(w) +
               ": its largest dimension is too large for its smallest)");
  }
  check_work_scale(s);
  if (top.has("contact")) {
    JsonObject c = top.object("contact");
    c.only_keys({"restitution", "friction", "solver", "iterations", "resting_speed"});
    s.restitution = c.number_or("restitution", s.restitution, {.min = 0, .max = 1});
    s.friction = c.number_or("friction", s.friction, {.min = 0});
    s.solver = Solver::kAccumulated;
    if (c.has("solver")) {
      const std::string name = c.string("solver");
      if (name == "passes") {
        s.solver = Solver::kPasses;
      } else if (name != "accumulated") {
        c.fail("solver", &c.raw().at("solver"), "one of: accumulated, passes");
      }
    }
    s.iterations = int(c.integer_or("iterations", s.iterations, 1, 1000));
    s.rest_speed = c.number_or("resting_speed", s.rest_speed, {.min = 0});
  }
  const wb::json& hinges = top.array_or_empty("hinges");
  for (std::size_t i = 0; i < hinges.size(); ++i) {
    JsonObject o = top.element("hinges", i);
    o.only_keys({"body", "anchor", "beta", "axis"});
    Hinge hg;
    hg.body = body_index(o, s);
    hg.anchor = vec3(o, "anchor");
    hg.beta = o.number_or("beta", hg.beta, {.min = 0, .max = 1});
    const Body& b = s.bodies[hg.body].body;
    hg.r_body = b.q.toRotationMatrix().transpose() * (hg.anchor - b.x);
    if (o.has("axis")) {  // a revolute hinge: the body turns about this world axis only
      hg.revolute = true;
      hg.axis = direction(o, "axis");
      hg.axis_body = b.q.toRotationMatrix().transpose() * hg.axis;
    }
    if (!hg.r_body.allFinite()) {
      o.fail("anchor", &o.raw().at("anchor"),
             "a point whose offset from body " + std::to_string(hg.body) + "'s centre is finite");
    }
    check_hinge(o, s.bodies[hg.body], hg);
    s.hinges.push_back(hg);
  }
  return s;
}

std::vector<Vec3> contact_points(const BodyDef& def, const Body& b, const Plane& plane) {
  const Mat3 R = b.q.toRotationMatrix();
  std::vector<Vec3> pts;
  if (def.shape == BodyDef::kSphere) {
    pts.push_back(b.x - def.radius * plane.normal);  // the lowest point
  } else if (def.shape == BodyDef::kBox) {
    //     6-------7      corner k = (+-a/2, +-b/2, +-c/2),
    //    /|      /|      bit 0: x, bit 1: y, bit 2: z (set: +)
    //   4-------5 |
    //   | 2-----|-3
    //   |/      |/
    //   0-------1
    for (int k = 0; k < 8; ++k) {
      const Vec3 c(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.5 : -0.5);
      pts.push_back(b.x + R * c.cwiseProduct(def.size));
    }
  } else {
    // Two rims of 16 points each: the edges a cylinder lands on.
    constexpr int kRim = 16;
    for (int end = -1; end <= 1; end += 2) {
      for (int k = 0; k < kRim; ++k) {
        const double a = 2.0 * M_PI * k / kRim;
        const Vec3 c(def.radius * std::cos(a), def.radius * std::sin(a), 0.5 * end * def.length);
        pts.push_back(b.x + R * c);
      }
    }
  }
  return pts;
}

double resolve_plane_passes(Body& b, const std::vector<Vec3>& points, const Vec3& point,
                            const Vec3& n, double e, double mu) {
  // One impulse at one point, with restitution and friction: the lab's own contact (R6),
  // prepared afresh (no totals kept, restitution at every closing speed) and solved once:
  // the normal impulse stops the approach and bounces, the friction stops the sliding
  // left after it or takes at most mu times the normal impulse (Coulomb).
  const auto impulse = [&](const Vec3& p) {
    Contact c;
    c.p = p;
    prepare_contact(b, n, e, 0.0, c);
    return solve_contact(b, c, n, mu);
  };
  double total = 0.0;
  for (int pass = 0; pass < kContactPasses; ++pass) {
    double applied = 0.0;
    for (const Vec3& p : points) {
      if ((p - point).dot(n) < kContactSlop) applied += impulse(p);
    }
    total += applied;
    if (applied == 0.0) break;
  }
  // Push the body out of the plane by the deepest penetration.
  double depth = 0.0;
  for (const Vec3& p : points) depth = std::max(depth, (point - p).dot(n));
  b.x += depth * n;
  return total;
}

namespace {

// Split impulses (the position part of the accumulated solver): "push" impulses,
// accumulated and >= 0 like the normal ones, on a pseudo-velocity (vp, wp) that
// starts at 0 each step, aiming at a normal pseudo-velocity of kPushBeta / h times
// each point's penetration. After the position update the body is moved by h vp and
// turned by h wp, omega turned with it (step): the push moves the body out and changes
// neither its velocities nor its kinetic energy.
// The impulses are the lab's own (R6): the pseudo-velocity is a copy of the body moving at
// (vp, wp), each contact a copy of the one the lab prepared (its r, K and mass_n) with no
// totals and the push as its target, given to the lab's solve_contact without friction.
void push_out(const Body& b, const std::vector<Contact>& contacts,
              const std::vector<double>& depth, const Vec3& n, double h, int iterations, Vec3& vp,
              Vec3& wp) {
  Body pseudo = b;
  pseudo.v = vp;
  pseudo.omega = wp;
  std::vector<Contact> push;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    if (!(depth[k] > 0)) continue;
    Contact c = contacts[k];
    c.Pn = 0;
    c.Pt.setZero();
    c.bias = kPushBeta / h * depth[k];
    push.push_back(c);
  }
  for (int it = 0; it < iterations; ++it) {
    for (Contact& c : push) solve_contact(pseudo, c, n, 0.0);
  }
  vp = pseudo.v;
  wp = pseudo.omega;
}

}  // namespace

double step(const Scene& scene, const Integrator& integ, double h, std::vector<Body>& bodies) {
  StepState fresh;
  return step(scene, integ, h, bodies, fresh);
}

double step(const Scene& scene, const Integrator& integ, double h, std::vector<Body>& bodies,
            StepState& state) {
  namespace budget = wb::budget;
  // Accumulate forces.
  budget::set_phase(budget::kForces);
  for (Body& b : bodies) {
    b.f.setZero();
    b.tau.setZero();
    apply_gravity(b, scene.g);
  }
  for (const PointForce& pf : scene.point_forces) {
    Body& b = bodies[pf.body];
    apply_force(b, pf.F, b.x + b.q.toRotationMatrix() * pf.point_body);
  }
  // Integrate velocities.
  budget::set_phase(budget::kStep);
  for (Body& b : bodies) {
    const Vec3 v0 = b.v, w0 = b.omega;
    integ.velocity(b, h);
    state.velocity_changed = state.velocity_changed || b.v != v0 || b.omega != w0;
  }
  // Constraint impulses: hinges, then contacts.
  budget::set_phase(budget::kHinges);
  for (const Hinge& hg : scene.hinges) {
    if (hg.revolute) {
      apply_revolute(bodies[hg.body], hg.r_body, hg.anchor, hg.axis_body, hg.axis, h, hg.beta);
    } else {
      apply_hinge(bodies[hg.body], hg.r_body, hg.anchor, h, hg.beta);
    }
  }
  budget::set_phase(budget::kContacts);
  const std::size_t np = scene.planes.size();
  std::vector<Vec3> vp(bodies.size(), Vec3::Zero()), wp(bodies.size(), Vec3::Zero());
  if (scene.solver == Solver::kAccumulated) state.contacts.resize(bodies.size() * np);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (std::size_t k = 0; k < np; ++k) {
      const Plane& pl = scene.planes[k];
      const std::vector<Vec3> points = contact_points(scene.bodies[i], bodies[i], pl);
      if (scene.solver == Solver::kPasses) {
        resolve_plane_passes(bodies[i], points, pl.point, pl.normal, scene.restitution,
                             scene.friction);
        continue;
      }
      // The points touching the plane, with the totals they kept from the last step
      // (a point that stopped touching starts again from zero).
      std::vector<Contact>& kept = state.contacts[i * np + k];
      kept.resize(points.size());
      std::vector<Contact> touching;
      std::vector<std::size_t> which;
      std::vector<double> depth;
      for (std::size_t j = 0; j < points.size(); ++j) {
        // A new contact needs the point in the plane; one that held the body in the
        // last step (Pn > 0) lasts while the point is less than the slop above it.
        const double d = (pl.point - points[j]).dot(pl.normal);
        if (d >= 0 || (kept[j].Pn > 0 && -d < kContactSlop)) {
          kept[j].p = points[j];
          touching.push_back(kept[j]);
          which.push_back(j);
          depth.push_back(d);
        } else {
          kept[j] = Contact{};
        }
      }
      if (touching.empty()) continue;
      solve_plane_contacts(bodies[i], touching, pl.normal, scene.restitution, scene.rest_speed,
                           scene.friction, scene.iterations);
      for (std::size_t j = 0; j < touching.size(); ++j) kept[which[j]] = touching[j];
      push_out(bodies[i], touching, depth, pl.normal, h, scene.iterations, vp[i], wp[i]);
    }
  }
  // Integrate positions (R4), then the push-out's pseudo-velocities move the bodies out
  // without changing their velocities: a translation h vp, and a turn by h |wp| about wp
  // that turns omega with the body. Its angular velocity in the body frame is kept, and so
  // is its kinetic energy: turning the body under an unchanged world omega would change
  // (1/2) omega . R I R^T omega (a box pushed out of the floor at t = 0 lost 2 % of it).
  budget::set_phase(budget::kStep);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Body& b = bodies[i];
    integrate_position(b, h);
    b.x += h * vp[i];
    const double angle = h * wp[i].norm();
    if (angle > 0) {
      const Eigen::AngleAxisd turn(angle, wp[i] / wp[i].norm());
      b.q = (Eigen::Quaterniond(turn) * b.q).normalized();
      b.omega = turn * b.omega;
    }
  }
  double drift = 0;
  state.hinge_angle = 0;
  for (const Hinge& hg : scene.hinges) {
    const Body& b = bodies[hg.body];
    const Mat3 R = b.q.toRotationMatrix();
    drift = std::max(drift, (b.x + R * hg.r_body - hg.anchor).norm());
    if (hg.revolute) {
      const Vec3 u = R * hg.axis_body;
      state.hinge_angle =
          std::max(state.hinge_angle, std::atan2(u.cross(hg.axis).norm(), u.dot(hg.axis)));
    }
  }
  return drift;
}

double work_scale(const Scene& scene, const std::vector<Body>& /*bodies*/) {
  return work_scale_of(scene);
}

Totals totals(const Scene& scene, const std::vector<Body>& bodies) {
  Totals t;
  for (const Body& b : bodies) {
    const Mat3 R = b.q.toRotationMatrix();
    const Vec3 Lspin = R * (b.I_body * (R.transpose() * b.omega));
    t.kinetic += 0.5 * b.m * b.v.squaredNorm() + 0.5 * b.omega.dot(Lspin);
    t.potential -= b.m * scene.g.dot(b.x);
    t.p += b.m * b.v;
    t.L += b.m * b.x.cross(b.v) + Lspin;
  }
  return t;
}

}  // namespace rigid
