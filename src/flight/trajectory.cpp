#include "flight/trajectory.hpp"

#include <algorithm>
#include <cmath>

namespace j232::flight {

namespace {
// Rodrigues' rotation of `axis` about the unit vector k by the angle whose cosine and sine are c, s.
Vec3 rotate(const Vec3& axis, const Vec3& k, double c, double s) { return axis * c + k.cross(axis) * s + k * (k.dot(axis)) * (1 - c); }
}  // namespace

Vec3 rotate_axis(const Vec3& axis, const Vec3& spin, double dt) {
  const double rate = spin.norm();
  if (rate * dt == 0.0) return axis;
  const double angle = rate * dt;
  return rotate(axis, spin / rate, std::cos(angle), std::sin(angle));
}

Vec3 drag_acceleration(const Drag& drag, const Vec3& velocity, const Vec3& axis) {
  const Vec3 v = velocity - drag.air;
  const double va = v.dot(axis);
  const Vec3 vn = v - va * axis;
  return -(drag.k_axial * std::abs(va) * va) * axis - (drag.k_normal * vn.norm()) * vn;
}

Vec3 acceleration(const Body& b, const Drag& drag) {
  return drag.on ? Vec3(kGravity + drag_acceleration(drag, b.velocity, b.axis)) : kGravity;
}

Body advance(const Body& b, double dt, const Drag& drag) { return advance(b, dt, drag, acceleration(b, drag)); }

Body advance(const Body& b, double dt, const Drag& drag, const Vec3& acceleration_at_start) {
  Body out = b;
  out.time = b.time + dt;
  // The axis at mid-step and at the end from one sine and cosine (of the half turn; the
  // whole turn by the double-angle formulas): this runs for every chord.
  const double rate = b.spin.norm();
  Vec3 mid_axis = b.axis;
  if (rate * dt != 0.0) {
    const Vec3 k = b.spin / rate;
    const double half = 0.5 * rate * dt, ch = std::cos(half), sh = std::sin(half);
    mid_axis = rotate(b.axis, k, ch, sh);
    out.axis = rotate(b.axis, k, ch * ch - sh * sh, 2 * sh * ch);
  }
  if (!drag.on) {
    out.position = b.position + b.velocity * dt + 0.5 * kGravity * dt * dt;
    out.velocity = b.velocity + kGravity * dt;
    return out;
  }
  auto accel = [&](const Vec3& v, const Vec3& axis) -> Vec3 { return kGravity + drag_acceleration(drag, v, axis); };
  const Vec3 k1v = acceleration_at_start, k1x = b.velocity;
  const Vec3 k2v = accel(b.velocity + 0.5 * dt * k1v, mid_axis), k2x = b.velocity + 0.5 * dt * k1v;
  const Vec3 k3v = accel(b.velocity + 0.5 * dt * k2v, mid_axis), k3x = b.velocity + 0.5 * dt * k2v;
  const Vec3 k4v = accel(b.velocity + dt * k3v, out.axis), k4x = b.velocity + dt * k3v;
  out.position = b.position + dt / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
  out.velocity = b.velocity + dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
  return out;
}

double chord_step(const Body& b, const Vec3& a, double tolerance, double max_length) {
  // Sag of a chord over dt under a transverse acceleration a: a dt^2 / 8.
  const double speed = b.velocity.norm();
  const Vec3 along = speed > 0 ? Vec3(b.velocity / speed) : Vec3::UnitZ();
  const double transverse = (a - a.dot(along) * along).norm();
  double dt = transverse > 0 ? std::sqrt(8.0 * tolerance / transverse) : 1.0;
  if (speed > 0) dt = std::min(dt, max_length / speed);
  return dt;
}

}  // namespace j232::flight
