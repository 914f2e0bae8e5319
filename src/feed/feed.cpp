#include "feed/feed.hpp"

#include <cmath>

#include "units/quantity.hpp"

namespace j232::feed {

namespace {
double wrap(double a) {  // to [0, 2 pi)
  a = std::fmod(a, units::two_pi);
  return a < 0 ? a + units::two_pi : a;
}
}  // namespace

NailDrop sample_drop(const scenario::Scenario& s, int nail_index, random::Stream& rng) {
  const auto& f = s.feed;
  const auto& n = s.nail;
  NailDrop d;
  d.station = nail_index % static_cast<int>(f.stations.size());
  const auto& st = f.stations[static_cast<std::size_t>(d.station)];
  // Nail as made: uniform within tolerance; mass follows length.
  const double length_factor = rng.uniform(-1.0, 1.0);
  d.length = n.length + n.length_tolerance * length_factor;
  d.mass = n.mass + n.mass_tolerance * rng.uniform(-1.0, 1.0);
  d.diameter = n.diameter;
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

std::vector<Edge> leading_edges(const blade::Blade& blade) {
  std::vector<Edge> edges;
  for (std::size_t a = 0; a < blade.arms.size(); ++a) edges.push_back({blade.arms[a].azimuth, blade.arms[a].tip_radius(), a});
  if (edges.empty()) {
    edges.push_back({0.0, blade.hub.reach(), std::nullopt});
    if (blade.hub.bar_mount == blade::BarMount::Centre) edges.push_back({units::pi, blade.hub.reach(), std::nullopt});
  }
  return edges;
}

double slab_window(const NailDrop& d, const scenario::BladeGeometry& g) {
  // Tip falls from the slab's top until the head clears its bottom: a drop of
  // thickness + vertical length of the nail, under gravity from fall_speed.
  const double depth = g.thickness + d.length * d.axis.z();
  const double v = d.fall_speed;
  return (-v + std::sqrt(v * v + 2.0 * kGravity * depth)) / kGravity;
}

std::optional<Strike> find_strike(const NailDrop& d, const std::vector<Edge>& edges, double omega, const scenario::BladeGeometry& g,
                                  int sense) {
  const double window = slab_window(d, g);
  const double phi0 = std::atan2(d.position.y(), d.position.x());
  std::optional<Strike> best;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    // The edge's angle is blade_phase + azimuth + omega t; the nail's azimuth phi(t)
    // drifts slowly. Solve edge(t) = phi(t) (mod 2 pi) by fixed-point iteration: it
    // contracts because the nail's angular drift is far slower than the blade.
    // Turning clockwise (sense -1) the edge closes the gap the other way round.
    const double gap = wrap(sense * (phi0 - d.blade_phase - edges[e].azimuth));
    double t = gap / omega;
    for (int it = 0; it < 4; ++it) {
      const Eigen::Vector2d p = d.position + d.drift * t;
      double dphi = std::atan2(p.y(), p.x()) - phi0;
      dphi = std::remainder(dphi, units::two_pi);
      t = (gap + sense * dphi) / omega;
    }
    if (t < 0.0 || t > window || (best && t >= best->time)) continue;
    const Eigen::Vector2d p = d.position + d.drift * t;
    const double r = p.norm();
    if (r > edges[e].reach || r <= 0.0) continue;
    Strike s;
    s.time = t;
    s.edge = e;
    s.radius = r;
    s.azimuth = std::atan2(p.y(), p.x());
    const double fall = d.fall_speed * t + 0.5 * kGravity * t * t;
    // Distance along the axis from the tip to the blade's mid-plane.
    const double tip_z = g.height + 0.5 * g.thickness - fall;
    const double along = std::clamp((g.height - tip_z) / d.axis.z(), 0.0, d.length);
    s.offset = along - 0.5 * d.length;
    s.nail_velocity = {d.drift.x(), d.drift.y(), -(d.fall_speed + kGravity * t)};
    s.contact_point = {p.x(), p.y(), g.height};
    best = s;
  }
  return best;
}

}  // namespace j232::feed
