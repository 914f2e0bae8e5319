#include "flight/mower.hpp"

#include <stdexcept>

#include "scenario/input_error.hpp"

namespace j232::flight {

Mower::Mower(const scenario::Scenario& s, scene::Engine engine) {
  try {
    scene_ = std::make_unique<scene::Scene>(scene::build_scene_soup(s), engine);
  } catch (const std::invalid_argument& e) {
    throw scenario::InputError(s.file, std::nullopt, s.meshes.empty() ? "housing" : "meshes", "", e.what());
  }
  guards_ = scene::scene_guards(s);  // numbered as the scene numbers them
  settings_ = FlightSettings(s, guards_);
  context_.scene = scene_.get();
  context_.settings = &settings_;
  context_.deck_radius = scene::mesh_roles(s).housing ? s.reach() + 0.05 : s.deck_radius();
  context_.counted_height = s.counted_height();
  context_.escape_radius = scene::escape_radius(s, scene_->soup());
  context_.board_near = scene::board_near_radius(scene_->soup());
  footprint_ = scene::deck_footprint(s, scene_->soup());
  deck_outline_ = DeckOutline(footprint_.outline);
  context_.deck_outline = &deck_outline_;
  context_.generated_deck = footprint_.generated;
  context_.skirt_bottom = footprint_.skirt_bottom;
  context_.deck_top = footprint_.top;
}

}  // namespace j232::flight
