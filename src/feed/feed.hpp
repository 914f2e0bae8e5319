#pragma once
// The J232 nail feed and the blade's strike (docs/model.md §5.1).
//
// Nails drop upright through a tube and funnel at feed stations. Time t = 0 is the
// moment a nail's tip reaches the top of the blade slab; at that moment the blade
// stands at a uniformly random phase. The nail is struck if a leading edge sweeps its
// azimuth while the nail still spans the slab and it lies within that edge's reach;
// otherwise it falls through (fed, not thrown). Between nails the blade is back at
// speed and radially aligned (the test feeds nails seconds apart).
#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "blade/blade.hpp"
#include "random/stream.hpp"
#include "scenario/scenario.hpp"
#include "units/quantity.hpp"

namespace j232::feed {

using Vec3 = Eigen::Vector3d;
inline constexpr double kGravity = units::standard_gravity;

struct NailDrop {
  int station = 0;
  double length = 0, mass = 0, diameter = 0;
  Vec3 axis = Vec3::UnitZ();                           // unit, tip -> head
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // axis at the blade plane at t = 0, from the spindle's axis, m
  Eigen::Vector2d drift = Eigen::Vector2d::Zero();     // horizontal velocity relative to the mower, m/s
  double fall_speed = 0;                               // downward, at t = 0, m/s
  double blade_phase = 0;                              // angle of the blade at t = 0, rad in [0, 2 pi)
};

NailDrop sample_drop(const scenario::Scenario& s, int nail_index, random::Stream& rng);

// A leading edge of the blade: the arm (or hub bar end) that sweeps through nails.
struct Edge {
  double azimuth = 0;              // in the blade frame, rad
  double reach = 0;                // m
  std::optional<std::size_t> arm;  // none: the hub bar itself
};
std::vector<Edge> leading_edges(const blade::Blade& blade);

struct Strike {
  double time = 0;  // s after t = 0
  std::size_t edge = 0;
  double radius = 0, azimuth = 0;  // of the contact, world
  double offset = 0;               // contact point from the nail's centre along its axis (+ toward the head), m
  Vec3 nail_velocity = Vec3::Zero();
  Vec3 contact_point = Vec3::Zero();
};

// Which edge meets the falling nail first, where along the nail, or nullopt (falls through).
// `drop.position` is relative to the spindle's axis; `sense` +1 counter-clockwise, -1 clockwise.
std::optional<Strike> find_strike(const NailDrop& drop, const std::vector<Edge>& edges, double omega,
                                  const scenario::BladeGeometry& geometry, int sense = +1);

// The time a nail spans the blade slab, from t = 0.
double slab_window(const NailDrop& drop, const scenario::BladeGeometry& geometry);

}  // namespace j232::feed
