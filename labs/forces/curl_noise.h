// TODO(F9) curl noise: a divergence-free flow as the curl of a potential, and drag towards it.
// Handout: handouts/forces.md#f9. Tests: [F9].
#pragma once
#include <vector>

#include "wb/noise.h"
#include "wb/types.h"

// A disc the flow goes around.
struct Disc {
  wb::Vec2 center{0, 0};  // (m)
  double radius = 1.0;    // (m), > 0
};

struct CurlNoiseParams {
  wb::Potential psi;            // the potential psi(x) (m^2/s); provided (wb::noise_potential)
  double b = 1.0;               // drag coefficient (kg/s), >= 0
  double h = 1e-4;              // step of the central differences (m), > 0
  std::vector<Disc> obstacles;  // may be empty
  double ramp = 1.0;            // d0: psi is ramped to 0 over this distance from an obstacle (m)
};

// Obstacles (Bridson, Hourihan and Nordenstam 2007): psi is multiplied by a
// smooth ramp of the distance to the nearest obstacle's edge, so that psi is 0
// on every edge, the edge is a streamline, and the flow goes around:
//
//   d(x)      = min over the discs k of (|x - center_k| - radius_k)  (< 0 inside a disc)
//   ramp(s)   = 1 for s >= 1, -1 for s <= -1, else 15/8 s - 10/8 s^3 + 3/8 s^5
//   psi_c(x)  = ramp(d(x) / d0) psi(x)        (psi_c = psi when there are no obstacles)
//
// Inputs: x a point (m), p the field (p.psi, p.obstacles, p.ramp = d0).
// Output: psi_c(x) (m^2/s).
double curl_noise_potential(const wb::Vec2& x, const CurlNoiseParams& p);

// The flow u = curl psi_c, in 2D u = (dpsi_c/dy, -dpsi_c/dx), each derivative
// by central differences with step p.h:
//   dpsi_c/dy ~ (psi_c(x + h e_y) - psi_c(x - h e_y)) / (2h), the same along e_x.
// Output: u(x) (m/s). Its divergence is zero: the flow neither sources nor sinks.
wb::Vec2 curl_noise_flow(const wb::Vec2& x, const CurlNoiseParams& p);

// Drag towards the flow, for every particle i:  f_i += b (u(x_i) - v_i).
// Inputs: x, v 2 x n positions (m) and velocities (m/s), p the field.
// Outputs: f 2 x n forces (N); add, do not overwrite.
void add_curl_noise(const wb::Mat2X& x, const wb::Mat2X& v, const CurlNoiseParams& p,
                    wb::Mat2X& f);
