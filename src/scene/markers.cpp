#include "scene/markers.hpp"

#include <cmath>

#include "scene/operator_zone.hpp"
#include "units/quantity.hpp"

namespace j232::scene {

namespace {
constexpr int kCircleSegments = 72;  // 5 degrees each

// A circle of radius r about c in the plane spanned by unit vectors u and v.
Polyline circle(std::string group, std::array<std::uint8_t, 3> colour, const Vec3& c, double r, const Vec3& u, const Vec3& v) {
  Polyline p{std::move(group), colour, {}, true};
  for (int i = 0; i < kCircleSegments; ++i) {
    const double a = units::two_pi * i / kCircleSegments;
    p.points.push_back(c + r * (std::cos(a) * u + std::sin(a) * v));
  }
  return p;
}
}  // namespace

std::vector<Polyline> mower_markers(const scenario::Scenario& s) {
  const Vec3 ex = Vec3::UnitX(), ey = Vec3::UnitY(), ez = Vec3::UnitZ();
  std::vector<Polyline> out;
  for (const auto& sp : s.spindles)
    out.push_back(circle("tip_circles", {0, 0, 0}, {sp.x, sp.y, sp.geometry.height}, sp.blade.tip_radius(), ex, ey));
  for (const auto& f : s.feed_stations()) {
    const double blade_z = s.spindles[f.spindle].geometry.height;
    const double top = blade_z + 0.5 * s.spindles[f.spindle].geometry.thickness + s.feed.drop_height;
    out.push_back({"feed_stations", {0, 158, 115}, {{s.station_x(f), s.station_y(f), top}, {s.station_x(f), s.station_y(f), blade_z}}});
  }
  if (s.zone.kind == scenario::OperatorZoneSpec::Kind::Derived) {
    const Vec3 seat(s.zone.seat_x, s.zone.seat_y, s.zone.seat_z);
    constexpr double arm = 0.05;
    for (const Vec3& axis : {ex, ey, ez}) out.push_back({"seat", {0, 0, 0}, {seat - arm * axis, seat + arm * axis}});
    const OperatorZone zone(s.zone, s.blade_plane());
    for (const auto& sphere : zone.envelope())
      for (const auto& [u, v] : {std::pair{ex, ey}, std::pair{ey, ez}, std::pair{ez, ex}})
        out.push_back(circle("reach_envelope", {230, 159, 0}, sphere.centre, sphere.radius, u, v));
  }
  return out;
}

}  // namespace j232::scene
