#pragma once
// What each surface does to a nail that meets it (docs/model.md §5.3), as one table built
// once from the scenario: a row per kind of surface and one per guard, so that the flight
// asks the row of the face it met instead of switching over surface kinds and reading the
// scenario's sections. The rows:
//   housing, deflector: steel plate; restitution falls with the normal speed (a power law),
//       Coulomb friction;
//   guard, chains: a curtain; a nail slips between the links with probability
//       `openness` keeping `pass_speed_factor` of its speed, or bounces (constant e);
//   guard, flap: a plate hinged at its top that the nail's impulse swings (the flap's mass
//       felt at the contact, I_hinge / d^2), with its restitution and friction;
//   ground: turf; restitution by the impact's angle to the surface, friction, and a
//       random tilt of the local normal (roughness); it holds a nail up (rest and sliding)
//       and a round object rolls on it; in a field it moves (the mower travels over it) and
//       the soil under it takes a strike that drives an object lying on it down;
//   board (target, operator zone): judged by the board model, not bounced off.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "blade/restitution.hpp"
#include "scenario/scenario.hpp"
#include "scene/soup.hpp"

namespace j232::flight {

struct SurfaceMaterial {
  enum class Response : std::uint8_t { Bounce, Curtain, Flap, Board };
  Response response = Response::Bounce;
  // Normal restitution: by the normal approach speed, or (turf) by the impact's angle.
  bool by_angle = false;
  blade::Restitution by_speed = blade::Restitution::constant(0.5);
  scenario::GroundSpec angle_law;  // its restitution_at (by_angle only)
  double friction = 0.4;
  double roughness = 0.0;  // rad: std. dev. of the local normal's tilt (0: smooth)
  double openness = 0.0, pass_speed_factor = 1.0;  // a curtain's
  bool holds_up = false;  // a nail can slide and come to rest on it
  double penetrability = 0.0;  // Young's S of soil a point-first nail sinks into (0: none)
  // The ground's, in a field: its velocity in the mower's frame (the mower travels over it;
  // an object at rest on it under the deck is carried toward the rear, where a blade may
  // strike it again), and soil under it that takes a strike driving an object lying on it
  // down (flight::soil_reaction). The J232 test's mower stands and its nails fall onto the blade.
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  bool takes_strikes = false;
  double rolling_resistance = 0.3;  // g: a round object rolling on it slows by this (GroundSpec)
  // A flap (Response::Flap): a plate hinged at `hinge_height` with moment of inertia
  // `flap_inertia` about its hinge (kg m^2, of the width that swings as one). Struck at
  // depth d below the hinge along its normal it moves as a mass I / d^2 there.
  double hinge_height = 0, flap_inertia = 0;
  double flap_mass_at(double height) const {
    const double d = std::max(hinge_height - height, 1e-3);
    return flap_inertia / (d * d);
  }

  // e for an impact at normal speed `normal_speed` whose path makes `angle` (rad) with the surface.
  double restitution(double normal_speed, double angle) const {
    return by_angle ? angle_law.restitution_at(angle) : by_speed.at(normal_speed);
  }
};

class SurfaceMaterials {
 public:
  SurfaceMaterials() = default;
  // `guards`: indexed as the scene numbers them (the soup's guard_index).
  SurfaceMaterials(const scenario::Scenario& s, const std::vector<scenario::GuardSpec>& guards);
  const SurfaceMaterial& of(scene::Surface surface, std::uint16_t guard) const {
    return surface == scene::Surface::Guard ? guards_.at(guard) : kinds_[static_cast<std::size_t>(surface)];
  }
  const SurfaceMaterial& ground() const { return kinds_[static_cast<std::size_t>(scene::Surface::Ground)]; }
  SurfaceMaterial& ground() { return kinds_[static_cast<std::size_t>(scene::Surface::Ground)]; }

 private:
  std::array<SurfaceMaterial, scene::kSurfaceKinds> kinds_{};
  std::vector<SurfaceMaterial> guards_;
};

}  // namespace j232::flight
