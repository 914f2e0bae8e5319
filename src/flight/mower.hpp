#pragma once
// The mower as its thrown objects meet it, built once from a scenario: the scene (deck,
// guards, ground; the board of a J232 test), the flight's settings, the deck's outline,
// and the flight context every thrown object starts from. The J232 simulator
// (assess/simulator.hpp) and the field's (field/field_simulator.hpp) share it.
#include <memory>
#include <vector>

#include "flight/deck_outline.hpp"
#include "flight/flight_settings.hpp"
#include "flight/nail_flight.hpp"
#include "scenario/scenario.hpp"
#include "scene/j232_setup.hpp"
#include "scene/scene.hpp"

namespace j232::flight {

class Mower {
 public:
  // Throws scenario::InputError for bad meshes.
  Mower(const scenario::Scenario& s, scene::Engine engine);
  Mower(const Mower&) = delete;
  Mower& operator=(const Mower&) = delete;

  const scene::Scene& scene() const { return *scene_; }
  const std::vector<scenario::GuardSpec>& guards() const { return guards_; }
  const scene::DeckFootprint& footprint() const { return footprint_; }
  const FlightSettings& settings() const { return settings_; }
  FlightSettings& settings() { return settings_; }
  // The context a flight starts from (its spindles and the zone left to the caller).
  const FlightContext& context() const { return context_; }
  FlightContext& context() { return context_; }

 private:
  std::unique_ptr<scene::Scene> scene_;
  std::vector<scenario::GuardSpec> guards_;
  FlightSettings settings_;  // built once from the scenario and the guards
  scene::DeckFootprint footprint_;
  DeckOutline deck_outline_;  // footprint_.outline, indexed for the flight
  FlightContext context_;
};

}  // namespace j232::flight
