#include "flight/trajectory.hpp"

#include <algorithm>
#include <cmath>

namespace j232::flight {

Vec3 rotate_axis(const Vec3& axis, const Vec3& spin, double dt) {
  const double rate = spin.norm();
  if (rate * dt == 0.0) return axis;
  const Vec3 k = spin / rate;
  const double angle = rate * dt, c = std::cos(angle), s = std::sin(angle);
  return axis * c + k.cross(axis) * s + k * (k.dot(axis)) * (1 - c);
}

Vec3 drag_acceleration(const Drag& drag, const Vec3& velocity, const Vec3& axis) {
  const Vec3 v = velocity - drag.air;
  const double va = v.dot(axis);
  const Vec3 vn = v - va * axis;
  return -(drag.k_axial * std::abs(va) * va) * axis - (drag.k_normal * vn.norm()) * vn;
}

Body advance(const Body& b, double dt, const Drag& drag) {
  Body out = b;
  out.time = b.time + dt;
  out.axis = rotate_axis(b.axis, b.spin, dt);
  if (!drag.on) {
    out.position = b.position + b.velocity * dt + 0.5 * kGravity * dt * dt;
    out.velocity = b.velocity + kGravity * dt;
    return out;
  }
  const Vec3 mid_axis = rotate_axis(b.axis, b.spin, 0.5 * dt);
  auto accel = [&](const Vec3& v, const Vec3& axis) -> Vec3 { return kGravity + drag_acceleration(drag, v, axis); };
  const Vec3 k1v = accel(b.velocity, b.axis), k1x = b.velocity;
  const Vec3 k2v = accel(b.velocity + 0.5 * dt * k1v, mid_axis), k2x = b.velocity + 0.5 * dt * k1v;
  const Vec3 k3v = accel(b.velocity + 0.5 * dt * k2v, mid_axis), k3x = b.velocity + 0.5 * dt * k2v;
  const Vec3 k4v = accel(b.velocity + dt * k3v, out.axis), k4x = b.velocity + dt * k3v;
  out.position = b.position + dt / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
  out.velocity = b.velocity + dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
  return out;
}

double chord_step(const Body& b, double tolerance, double max_length, const Drag& drag) {
  // Sag of a chord over dt under a transverse acceleration a: a dt^2 / 8.
  Vec3 a = kGravity;
  if (drag.on) a += drag_acceleration(drag, b.velocity, b.axis);
  const double speed = b.velocity.norm();
  const Vec3 along = speed > 0 ? Vec3(b.velocity / speed) : Vec3::UnitZ();
  const double transverse = (a - a.dot(along) * along).norm();
  double dt = transverse > 0 ? std::sqrt(8.0 * tolerance / transverse) : 1.0;
  if (speed > 0) dt = std::min(dt, max_length / speed);
  return dt;
}

}  // namespace j232::flight
