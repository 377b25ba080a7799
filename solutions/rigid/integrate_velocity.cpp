#include "integrate_velocity.h"

#include <Eigen/Dense>

// TODO(R5) semi-implicit Euler for the velocities: explicit and implicit gyroscopic
// term (see integrate_velocity.h).
void integrate_velocity_explicit(rigid::Body& b, double h) {
  // Integrate the linear velocity.
  b.v += h / b.m * b.f;
  // Integrate the angular velocity, gyroscopic term at the start of the step.
  const rigid::Mat3 R = b.q.toRotationMatrix();
  const rigid::Mat3 I = R * b.I_body * R.transpose();
  const rigid::Mat3 I_inv = R * b.I_body.diagonal().cwiseInverse().asDiagonal() * R.transpose();
  b.omega += h * I_inv * (b.tau - b.omega.cross(I * b.omega));
}

void integrate_velocity_implicit(rigid::Body& b, double h) {
  // Integrate the linear velocity.
  b.v += h / b.m * b.f;
  // Gyroscopic term: one Newton step on the body-frame equation.
  const rigid::Mat3 R = b.q.toRotationMatrix();
  const rigid::Mat3& Ib = b.I_body;
  const rigid::Vec3 w = R.transpose() * b.omega;  // body frame
  const rigid::Vec3 residual = h * w.cross(Ib * w);
  const rigid::Mat3 J = Ib + h * (rigid::skew(w) * Ib - rigid::skew(Ib * w));
  const rigid::Vec3 w_new = w - J.partialPivLu().solve(residual);
  // Back to the world frame; the torque taken explicitly.
  const rigid::Mat3 I_inv = R * Ib.diagonal().cwiseInverse().asDiagonal() * R.transpose();
  b.omega = R * w_new + h * I_inv * b.tau;
}
