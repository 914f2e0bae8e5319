#include "flight/surface_material.hpp"

#include "scene/j232_setup.hpp"

namespace j232::flight {

SurfaceMaterials::SurfaceMaterials(const scenario::Scenario& s, const std::vector<scenario::GuardSpec>& guards) {
  SurfaceMaterial steel;
  steel.by_speed = s.housing.restitution;
  steel.friction = s.housing.friction;
  kinds_[static_cast<std::size_t>(scene::Surface::Housing)] = steel;
  kinds_[static_cast<std::size_t>(scene::Surface::Deflector)] = steel;
  SurfaceMaterial turf;
  turf.by_angle = true;
  turf.angle_law = s.ground;
  turf.friction = s.ground.friction;
  turf.roughness = s.ground.roughness;
  turf.holds_up = true;
  turf.penetrability = s.ground.penetrability;
  turf.rolling_resistance = s.ground.rolling_resistance;
  if (s.field.present) {
    turf.velocity = {-s.field.ground_speed, 0.0, 0.0};  // the turf, seen from the travelling mower
    turf.takes_strikes = true;
  }
  kinds_[static_cast<std::size_t>(scene::Surface::Ground)] = turf;
  SurfaceMaterial board;
  board.response = SurfaceMaterial::Response::Board;
  kinds_[static_cast<std::size_t>(scene::Surface::TargetOutside)] = board;
  kinds_[static_cast<std::size_t>(scene::Surface::TargetZone)] = board;
  // (No row of kinds_ for guards: every guard has its own, below; of() looks there.)
  for (const auto& g : guards) {
    SurfaceMaterial guard;
    guard.response = g.kind == scenario::GuardSpec::Kind::Flap ? SurfaceMaterial::Response::Flap : SurfaceMaterial::Response::Curtain;
    guard.by_speed = blade::Restitution::constant(g.restitution);
    guard.friction = g.friction;
    guard.openness = g.openness;
    guard.pass_speed_factor = g.pass_speed_factor;
    if (g.kind == scenario::GuardSpec::Kind::Flap) {
      const scene::FlapGeometry f = scene::flap_geometry(s, g);
      const double height = f.hinge - f.bottom, mass = g.density * g.thickness * f.swinging * height;
      guard.hinge_height = f.hinge;
      guard.flap_inertia = mass * height * height / 3;  // a uniform plate about its edge
    }
    guards_.push_back(guard);
  }
}

}  // namespace j232::flight
