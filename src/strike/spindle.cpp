#include "strike/spindle.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "scenario/input_error.hpp"
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

std::vector<Spindle> scenario_spindles(const scenario::Scenario& s, const blade::Restitution& on_blade) {
  std::vector<Spindle> out;
  for (std::size_t k = 0; k < s.spindles.size(); ++k) {
    const auto& spec = s.spindles[k];
    try {
      Spindle sp(spec.blade, spec.geometry, on_blade);
      sp.centre = {spec.x, spec.y};
      sp.sense = spec.sense;
      sp.reference_search = s.run.reference_contact_search;
      sp.law = s.run.restitution_law;
      out.push_back(std::move(sp));
    } catch (const std::invalid_argument& e) {
      throw scenario::InputError(s.file, std::nullopt, s.spindles.size() == 1 ? "blade" : fmt::format("spindles[{}].blade", k + 1), "",
                                 e.what());
    }
  }
  return out;
}

}  // namespace j232::strike
