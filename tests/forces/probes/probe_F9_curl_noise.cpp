// Diagnosis probes of F9 (tests/common/wb_probe.h): the ramped potential alone (within the
// ramp of one disc, beyond it, between two discs), the flow (no obstacle, then near one), the
// drag. psi is a quadratic, psi = x y + y^2/2 + x^2/4, so that central differences are exact
// and h = 0.1 makes a one-sided difference show; its flow is u = (x + y, -(y + x/2)). One probe
// ("flow-cubic") adds a cubic term, where the central difference depends on its step, and has no
// obstacle: a wrong step shows there, no ramp mistake does.
#include "curl_noise.h"
#include "wb_probe.h"

// The lab's probe files compile as one unit (cmake/labs.cmake): each keeps its helpers in a
// namespace of its own.
namespace probe_F9_curl_noise {

using wbprobe::cols;

namespace {
using wb::Vec2;
CurlNoiseParams field(std::vector<Disc> obstacles, double ramp, double b) {
  CurlNoiseParams p;
  p.psi = [](const Vec2& x) {
    return x.x() * x.y() + 0.5 * x.y() * x.y() + 0.25 * x.x() * x.x();
  };
  p.b = b, p.h = 0.1, p.obstacles = std::move(obstacles), p.ramp = ramp;
  return p;
}
void in(wbprobe::Probe& P, const CurlNoiseParams& p) {
  P.note("psi(x) = x y + y^2/2 + x^2/4");
  for (const Disc& d : p.obstacles) P.in("disc.center", d.center), P.in("disc.radius", d.radius);
  P.in("ramp", p.ramp), P.in("h", p.h), P.in("b", p.b);
}
void potential(wbprobe::Probe& P, const Vec2& x, const CurlNoiseParams& p) {
  P.call("curl_noise_potential");
  P.in("x", x), in(P, p);
  P.out("returned", curl_noise_potential(x, p));
}
void flow(wbprobe::Probe& P, const Vec2& x, const CurlNoiseParams& p) {
  P.call("curl_noise_flow");
  P.in("x", x), in(P, p);
  P.out("returned", curl_noise_flow(x, p));
}
void drag(wbprobe::Probe& P, const wb::Mat2X& x, const wb::Mat2X& v, const CurlNoiseParams& p,
          wb::Mat2X f) {
  P.call("add_curl_noise");
  P.in("x", x), P.in("v", v), in(P, p), P.in("f", f);
  add_curl_noise(x, v, p, f);
  P.out("f", f);
}
const Disc kDisc{Vec2(0.5, -0.5), 1.2};
}  // namespace

WB_PROBE("F9", "potential-free", "curl_noise_potential with no obstacle: psi itself") {
  P.simple();
  potential(P, Vec2(1, 2), field({}, 1, 1));
}
// The ramp of the potential.
WB_PROBE("F9", "potential-near",
         "curl_noise_potential 1.3 from a disc's edge, ramp distance 2.5") {
  P.simple();
  potential(P, Vec2(3, -0.5), field({kDisc}, 2.5, 1));
}
WB_PROBE("F9", "potential-far",
         "curl_noise_potential 2.8 from a disc's edge, beyond the ramp 2.5") {
  P.simple();
  potential(P, Vec2(4.5, -0.5), field({kDisc}, 2.5, 1));
}
WB_PROBE("F9", "potential-two", "curl_noise_potential between two discs, nearer to the second") {
  P.simple();
  potential(P, Vec2(3, -0.5), field({kDisc, Disc{Vec2(4, 0.5), 0.5}}, 2.5, 1));
}
// The curl (before the obstacles: a curl mistake's counterexample is a flow with no obstacle).
WB_PROBE("F9", "flow-free", "curl_noise_flow with no obstacle, h = 0.1") {
  flow(P, Vec2(1, 2), field({}, 1, 1));
}
// The step: psi with a cubic term, whose central difference is off the derivative by h^2/6 times
// its third derivative, so that a step other than p.h shows; no obstacle, so that no ramp
// mistake does.
WB_PROBE("F9", "flow-cubic",
         "curl_noise_flow with no obstacle, psi = x y + y^2/2 + x^2/4 + x^3/2 - y^3/3, h = 0.1") {
  CurlNoiseParams p = field({}, 1, 1);
  p.psi = [](const Vec2& x) {
    return x.x() * x.y() + 0.5 * x.y() * x.y() + 0.25 * x.x() * x.x() +
           0.5 * x.x() * x.x() * x.x() - x.y() * x.y() * x.y() / 3;
  };
  P.call("curl_noise_flow");
  P.in("x", Vec2(1, 2));
  P.note("psi(x) = x y + y^2/2 + x^2/4 + x^3/2 - y^3/3");
  P.in("h", p.h);
  P.out("returned", curl_noise_flow(Vec2(1, 2), p));
}
// The obstacles, in one group: the potential within the ramp of a disc, beyond it, between two
// discs, deep inside a disc wider than the ramp (s < -1), nearer to a large disc's edge than to
// a small one's whose centre is nearer, and the flow within the ramp.
WB_PROBE("F9", "obstacles",
         "curl_noise_potential 1.3 and 2.8 from a disc's edge (ramp 2.5), between two discs, "
         "3.29 inside a disc of radius 4, 0.31 from its edge with a small disc's centre nearer; "
         "curl_noise_flow 1.3 from the edge") {
  P.call("curl_noise_potential, curl_noise_flow");
  const CurlNoiseParams one = field({kDisc}, 2.5, 1);
  const CurlNoiseParams two = field({kDisc, Disc{Vec2(4, 0.5), 0.5}}, 2.5, 1);
  const CurlNoiseParams big = field({Disc{Vec2(-4, 1), 4}, Disc{Vec2(1.2, 1.6), 0.3}}, 2.5, 1);
  in(P, two);
  P.note(
      "near and far: the first disc alone; inside and edge: discs (-4, 1) r 4, (1.2, 1.6) r 0.3");
  P.in("x (near, far, between, inside, edge)",
       wbprobe::cols({{3, -0.5}, {4.5, -0.5}, {3, -0.5}, {-3.5, 1.5}, {0.3, 1.3}}));
  // One group (a ramp mistake shows in either), two outputs (a flow mistake in u alone): the
  // counterexample then names the one that is wrong.
  P.group("obstacles");
  P.out("psi_c (near, far, between, inside, edge)",
        wbprobe::vec(
            {curl_noise_potential(Vec2(3, -0.5), one), curl_noise_potential(Vec2(4.5, -0.5), one),
             curl_noise_potential(Vec2(3, -0.5), two), curl_noise_potential(Vec2(-3.5, 1.5), big),
             curl_noise_potential(Vec2(0.3, 1.3), big)}));
  P.out("u near", curl_noise_flow(Vec2(3, -0.5), one));
  P.group("");
}
WB_PROBE("F9", "flow-near", "curl_noise_flow 1.3 from a disc's edge, ramp distance 2.5") {
  P.simple();
  flow(P, Vec2(3, -0.5), field({kDisc}, 2.5, 1));
}
// The drag: the first and last particles move with the flow.
WB_PROBE("F9", "drag",
         "add_curl_noise, no obstacle, b = 2: a particle at rest between two that move with the "
         "flow") {
  drag(P, cols({{1, 2}, {-1, 0.5}, {2, -1}}), cols({{3, -2.5}, {0, 0}, {1, 0}}), field({}, 1, 2),
       cols({{0, 0}, {0, 0}, {0, 0}}));
}
// Every particle, near a disc, and what f held.
WB_PROBE("F9", "several", "add_curl_noise on three particles near a disc, f holding forces") {
  drag(P, cols({{3, -0.5}, {-2, 0.5}, {0, -3}}), cols({{0.5, 0}, {0, 0}, {-1, 1}}),
       field({kDisc}, 2.5, 0.5), cols({{1, 0}, {0, 1}, {-1, 0}}));
}

}  // namespace probe_F9_curl_noise
