#include "strike/spindle.hpp"

#include <algorithm>
#include <cmath>

#include "units/quantity.hpp"
#include "units/sin_cos.hpp"

namespace j232::strike {

std::vector<Edge> leading_edges(const blade::Blade& blade) {
  std::vector<Edge> edges;
  for (std::size_t a = 0; a < blade.arms.size(); ++a) edges.push_back({blade.arms[a].azimuth, blade.arms[a].tip_radius(), a});
  if (edges.empty()) {
    edges.push_back({0.0, blade.hub.reach(), std::nullopt});
    if (blade.hub.bar_mount == blade::BarMount::Centre) edges.push_back({units::pi, blade.hub.reach(), std::nullopt});
  }
  return edges;
}

EdgeShape edge_shape(const scenario::BladeGeometry& g) {
  EdgeShape s;
  s.thickness = g.thickness;
  s.width = g.edge.width;
  s.bevel_angle = g.edge.bevel_angle;
  s.bevel_on_top = g.edge.bevel_side == scenario::EdgeSpec::Side::Top;
  s.sail_height = g.edge.sail_height;
  s.sail_angle = g.edge.sail_angle;
  return s;
}

Spindle::Spindle(const blade::Blade& b, const scenario::BladeGeometry& g, const blade::Restitution& e)
    : height(g.height),
      blade(b),
      model(b),
      edges(leading_edges(b)),
      section(edge_shape(g)),
      restitution(e),
      friction(g.edge.friction) {
  for (const auto& edge : edges) reach = std::max(reach, edge.reach);
}

void Spindle::frame(std::size_t e, double phase, double t, Vec3& radial, Vec3& forward) const {
  const double angle = phase + sense * omega() * t + edges[e].azimuth;
  const units::SinCos sc = units::sin_cos(angle);
  const double c = sc.cos, s = sc.sin;
  radial = {c, s, 0.0};
  forward = {-sense * s, sense * c, 0.0};
}

Vec3 Spindle::velocity_at(const Vec3& point) const {
  const double w = sense * omega();
  return {-w * (point.y() - centre.y()), w * (point.x() - centre.x()), 0.0};
}

}  // namespace j232::strike
