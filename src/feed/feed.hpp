#pragma once
// The J232 nail feed (docs/model.md §5.1). Nails drop upright through a tube and funnel
// at feed stations. Time t = 0 is the moment a nail's tip reaches the top face of the
// blade it is fed to; at that moment the blade stands at a uniformly random phase.
// Between nails the blade is back at speed and radially aligned (the test feeds nails
// seconds apart). Whether, where and how the blade strikes the falling nail is the
// strike stage's (strike/contact_search.hpp): the feed says how the nail falls.
#include <Eigen/Dense>

#include "projectile/projectile.hpp"
#include "random/stream.hpp"
#include "scenario/scenario.hpp"
#include "strike/contact_search.hpp"
#include "units/quantity.hpp"

namespace j232::feed {

using Vec3 = Eigen::Vector3d;
inline constexpr double kGravity = units::standard_gravity;

struct NailDrop {
  int station = 0;
  std::size_t spindle = 0;  // the spindle whose blade the station feeds
  projectile::Projectile nail;
  Vec3 axis = Vec3::UnitZ();                           // unit, tip -> head
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // the tip at t = 0, from the spindle's axis, m
  Eigen::Vector2d drift = Eigen::Vector2d::Zero();     // horizontal velocity relative to the mower, m/s
  double fall_speed = 0;                               // downward, at t = 0, m/s
  double blade_phase = 0;                              // angle of the blade at t = 0, rad in [0, 2 pi)
};

NailDrop sample_drop(const scenario::Scenario& s, int nail_index, random::Stream& rng);

// The falling nail as the strike stage searches it: from before its tip reaches the top
// of the blade's section (a sail stands above the plate) to after its head has passed
// below the blade. `spindle` is the one the station feeds; positions are in the world.
struct FallThrough {
  strike::Motion motion;
  double until = 0;  // s: the nail is below the blade from then on
};
FallThrough fall_through(const NailDrop& drop, const strike::Spindle& spindle);

}  // namespace j232::feed
