#pragma once
// A turning blade in the scene (docs/model.md §5.1-5.2): where it is, how it turns, its
// arms' edges and its section, its mass model for impulses, and the nail-on-blade
// restitution and friction. Between passes the blade is back at its speed and radially
// aligned (the report's assumption: the drive restores it; a nail is 1/5000 of the blade).
//
// Angles: a spindle's blade stands at angle `phase` at time 0 (the nail's own clock) and
// turns at sense * omega: counter-clockwise seen from above for sense +1, clockwise for
// -1. An edge at `azimuth` in the blade frame points along phase + sense * omega * t +
// azimuth; the blade moves along e_t = sense * z x e_r there.
#include <Eigen/Dense>
#include <array>
#include <optional>
#include <vector>

#include "blade/blade.hpp"
#include "blade/blade_model.hpp"
#include "blade/restitution.hpp"
#include "scenario/scenario.hpp"
#include "strike/blade_section.hpp"

namespace j232::strike {

using Vec3 = Eigen::Vector3d;

// A leading edge of the blade: the arm (or hub bar end) that sweeps through nails.
struct Edge {
  double azimuth = 0;              // in the blade frame, rad
  double reach = 0;                // m
  std::optional<std::size_t> arm;  // none: the hub bar itself
};
std::vector<Edge> leading_edges(const blade::Blade& blade);

// The section of a scenario's blade edge.
EdgeShape edge_shape(const scenario::BladeGeometry& geometry);

struct Spindle {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // m, world
  double height = 0.076;                             // blade mid-plane above ground, m
  int sense = +1;                                    // +1 counter-clockwise, -1 clockwise, seen from above
  blade::Blade blade;
  blade::BladeModel model;
  std::vector<Edge> edges;
  double reach = 0.0;  // tip radius: no edge reaches beyond
  BladeSection section;
  blade::Restitution restitution = blade::Restitution::constant(0.9);  // nail on blade
  double friction = 0.4;                                               // nail on blade, Coulomb
  bool reference_search = false;  // contacts by the fixed-step reference ([run] contact_search)
  scenario::RestitutionLaw law = scenario::RestitutionLaw::Energetic;  // [run] restitution_law

  Spindle(const blade::Blade& blade, const scenario::BladeGeometry& geometry, const blade::Restitution& restitution);
  double omega() const { return blade.omega; }
  // The radial and forward (direction of motion) unit vectors of edge `e` at time t.
  void frame(std::size_t e, double phase, double t, Vec3& radial, Vec3& forward) const;
  // The blade's velocity at a world point (rigid rotation about the spindle's axis).
  Vec3 velocity_at(const Vec3& point) const;
};

// The blades' phases at time 0 for one nail (one per spindle; the report's blade is one).
inline constexpr std::size_t kMaxSpindles = 8;
struct BladePhases {
  std::array<double, kMaxSpindles> at_zero{};
};

// The scenario's turning blades, each where its spindle stands, striking with `on_blade`
// (the nail's restitution, or a field object's). Throws scenario::InputError naming the
// blade for an unsound one.
std::vector<Spindle> scenario_spindles(const scenario::Scenario& s, const blade::Restitution& on_blade);

}  // namespace j232::strike
