#pragma once
// A turning blade in the scene (docs/model.md §5.2a). The blade sweeps its disc, a slab
// of its thickness inside its tip circle, and strikes whatever its leading edges meet
// there: the falling nail of the feed, and a thrown nail that comes back into the disc
// (turned back by the skirt, bounced off the turf). Between strikes the blade is back at
// its speed and radially aligned (the report's assumption: the drive restores it).
//
// Angles: a spindle's blade stands at angle `phase` at time 0 (the nail's own clock,
// which starts as its tip reaches the top of the slab it is fed to) and turns at
// sense * omega: counter-clockwise seen from above for sense +1, clockwise for -1. An
// edge at `azimuth` in the blade frame points along phase + sense * omega * t + azimuth.
#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "blade/blade.hpp"
#include "blade/blade_model.hpp"
#include "blade/impact.hpp"
#include "blade/restitution.hpp"
#include "feed/feed.hpp"

namespace j232::feed {

struct Spindle {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // m, world
  double height = 0.076;                             // blade mid-plane above ground, m
  double thickness = 0.006;                          // m
  double lift_angle = 0.0;                           // rad: the edge's bevel tilts the contact normal up
  int sense = +1;                                    // +1 counter-clockwise, -1 clockwise, seen from above
  blade::Blade blade;
  blade::BladeModel model;
  std::vector<Edge> edges;
  double reach = 0.0;                                                  // tip radius: no edge reaches beyond
  blade::Restitution restitution = blade::Restitution::constant(0.9);  // nail on blade

  Spindle(const blade::Blade& blade, const scenario::BladeGeometry& geometry, const blade::Restitution& restitution);
  double omega() const { return blade.omega; }
};

// The blades' phases at time 0 for one nail (one per spindle; the report's blade is one).
inline constexpr std::size_t kMaxSpindles = 8;
struct BladePhases {
  std::array<double, kMaxSpindles> at_zero{};
};

// Where and when an edge meets a nail.
struct BladeHit {
  std::size_t spindle = 0, edge = 0;
  double time = 0;                 // s, on the nail's clock
  double radius = 0, azimuth = 0;  // of the nail about the spindle axis, world azimuth
};

// What decides whether a nail reaches into the blade's slab: its length, its axis at the
// chord's start and its spin, about which the axis turns (perpendicular to it: a slender
// rod). A struck nail's axis turns through many radians within a chord.
class SweptRod {
 public:
  SweptRod() = default;
  SweptRod(double length, const Eigen::Vector3d& axis, const Eigen::Vector3d& spin);
  double length() const { return length_; }
  // The most the turning rod reaches up or down from its centre (the amplitude of its
  // axis' vertical component over a turn, times half its length).
  double max_half_height() const { return max_half_height_; }
  // The vertical component of the axis dt after t0.
  double axis_z_after(double dt) const;

 private:
  double length_ = 0, rate_ = 0, max_half_height_ = 0;
  Eigen::Vector3d axis_ = Eigen::Vector3d::UnitZ(), across_ = Eigen::Vector3d::Zero();  // across: the axis a quarter turn on
};

// The first time in (after, t1] at which an edge of `spindle` sweeps a nail whose centre
// moves from p0 (at t0) with constant velocity v, while some part of the nail lies in the
// blade's slab and within that edge's reach. The slab test is made with the nail's axis
// as it stands at that instant (an edge that passes while the turning nail lies flat
// enough to clear the slab misses it, and a later pass may not). A chord of a flight is
// short enough to be taken as straight.
std::optional<BladeHit> first_sweep(const Spindle& spindle, double phase, const Eigen::Vector3d& p0, const Eigen::Vector3d& v, double t0,
                                    double t1, const SweptRod& rod, double after);

// A nail (rigid slender rod) as the blade meets it.
struct NailAtBlade {
  double mass = 0, length = 0;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero(), spin = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // tip -> head
  double offset = 0;                                // contact point from the nail's centre along its axis, m
};

// The impact of the edge `hit.edge` on the nail at hit.radius / hit.azimuth: nothing when
// the nail outruns the edge there (or the radius is off the blade).
std::optional<blade::ContactOutcome> strike(const Spindle& spindle, const BladeHit& hit, const NailAtBlade& nail);

}  // namespace j232::feed
