#include "feed/feed.hpp"

#include <cmath>

#include "units/quantity.hpp"

namespace j232::feed {

NailDrop sample_drop(const scenario::Scenario& s, int nail_index, random::Stream& rng) {
  const auto& f = s.feed;
  const auto& n = s.nail;
  NailDrop d;
  d.station = nail_index % static_cast<int>(s.feed_station_count());
  const scenario::FeedStation st = s.feed_station(static_cast<std::size_t>(d.station));
  d.spindle = st.spindle;
  // Nail as made: uniform within tolerance; mass follows length.
  const double length_factor = rng.uniform(-1.0, 1.0);
  d.nail = projectile::Projectile::capsule(n.length + n.length_tolerance * length_factor, n.diameter,
                                           n.mass + n.mass_tolerance * rng.uniform(-1.0, 1.0));
  // Outlet: uniform over the funnel's outlet disc (sqrt for area-uniform radius).
  const double rho = 0.5 * f.outlet_diameter * std::sqrt(rng.uniform());
  const double psi = units::two_pi * rng.uniform();
  d.position = {st.radius * std::cos(st.azimuth) + rho * std::cos(psi), st.radius * std::sin(st.azimuth) + rho * std::sin(psi)};
  // Tilt: uniform over the spherical cap of half-angle tilt_max about vertical.
  const double cos_tilt = 1.0 - rng.uniform() * (1.0 - std::cos(f.tilt_max));
  const double sin_tilt = std::sqrt(std::max(0.0, 1.0 - cos_tilt * cos_tilt));
  const double tilt_azimuth = units::two_pi * rng.uniform();
  d.axis = {sin_tilt * std::cos(tilt_azimuth), sin_tilt * std::sin(tilt_azimuth), cos_tilt};
  // Free fall from the outlet to the top of the blade slab.
  const double v0 = f.outlet_speed_max * rng.uniform();
  d.fall_speed = std::sqrt(v0 * v0 + 2.0 * kGravity * f.drop_height);
  d.drift = {-f.ground_speed, 0.0};
  d.blade_phase = units::two_pi * rng.uniform();
  return d;
}

FallThrough fall_through(const NailDrop& d, const strike::Spindle& sp) {
  FallThrough f;
  const double thickness = sp.section.shape().thickness, half = 0.5 * thickness;
  // The tip (the end of the capsule) at the top face at t = 0.
  const Vec3 tip(sp.centre.x() + d.position.x(), sp.centre.y() + d.position.y(), sp.height + half);
  const Vec3 centre0 = tip + (0.5 * d.nail.length) * d.axis;
  // Back in time until the tip stands a millimetre above the section's top (the sail).
  const double above = sp.section.top() - half + 1e-3;
  const double v = d.fall_speed;
  const double before = std::max(0.0, v * v - 2 * kGravity * above) > 0 ? (v - std::sqrt(v * v - 2 * kGravity * above)) / kGravity
                                                                         : v / kGravity;
  f.motion.t0 = -before;
  f.motion.a = {0.0, 0.0, -kGravity};
  f.motion.v0 = {d.drift.x(), d.drift.y(), -(v - kGravity * before)};
  f.motion.p0 = centre0 - before * Vec3(d.drift.x(), d.drift.y(), -v) + 0.5 * before * before * f.motion.a;
  f.motion.axis0 = d.axis;
  f.motion.spin = Vec3::Zero();
  // Until the head is a diameter below the bottom face.
  const double depth = thickness + d.nail.length * d.axis.z() + d.nail.diameter;
  f.until = (-v + std::sqrt(v * v + 2.0 * kGravity * depth)) / kGravity;
  return f;
}

}  // namespace j232::feed
