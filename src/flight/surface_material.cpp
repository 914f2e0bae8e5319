#include "flight/surface_material.hpp"

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
  kinds_[static_cast<std::size_t>(scene::Surface::Ground)] = turf;
  SurfaceMaterial board;
  board.response = SurfaceMaterial::Response::Board;
  kinds_[static_cast<std::size_t>(scene::Surface::TargetOutside)] = board;
  kinds_[static_cast<std::size_t>(scene::Surface::TargetZone)] = board;
  SurfaceMaterial curtain;
  curtain.response = SurfaceMaterial::Response::Curtain;
  // (No row of kinds_ for guards: every guard has its own, below; of() looks there.)
  for (const auto& g : guards) {
    curtain.by_speed = blade::Restitution::constant(g.restitution);
    curtain.friction = g.friction;
    curtain.openness = g.openness;
    curtain.pass_speed_factor = g.pass_speed_factor;
    guards_.push_back(curtain);
  }
}

}  // namespace j232::flight
