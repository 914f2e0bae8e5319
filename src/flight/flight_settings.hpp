#pragma once
// What a nail's flight needs to know of the scenario, built once by the simulator and
// handed down (the flight never reads the whole Scenario): its numerical and physical
// limits, the board's model, the deck's named openings (to say how a nail left), and the
// surfaces' materials.
#include <Eigen/Dense>
#include <vector>

#include "units/arc.hpp"
#include "flight/surface_material.hpp"
#include "scenario/scenario.hpp"

namespace j232::flight {

struct FlightSettings {
  double chord_tolerance = 0.001;  // m: the most a chord may sag from the path
  double time_limit = 3.0;         // s of flight per nail
  int max_bounces = 400;             // bounces: contacts approaching at least sqrt(2 g D)
  int max_gentle_contacts = 100000;  // gentle contacts: slower (a sustained contact's micro-impacts)
  int max_strikes = 20500;            // blade strikes of one nail (scenario::Scenario::max_strikes)
  int max_contacts_per_pass = 20000;  // contacts of one pass of an edge (scenario::RunSpec)
  double rest_speed = 0.3;  // m/s: slower after a bounce (and turning slower at its ends) is at rest
  scenario::RestitutionLaw law = scenario::RestitutionLaw::Energetic;  // how a bounce's restitution is read
  scenario::ContactModel contacts = scenario::ContactModel::Sequential;  // contacts at one instant: one after the other, or together
  scenario::BladePush blade_push = scenario::BladePush::Held;           // a knife's push on a sphere: held on the face, or contact by contact
  scenario::BoardSpec board;
  // The generated deck's discharge openings, for naming the way out.
  struct Opening {
    units::Arc azimuth;
    double top = 0;
  };
  std::vector<Opening> openings;
  // What each surface does, the ground's motion and soil in a field among it.
  SurfaceMaterials materials;

  FlightSettings() = default;
  // `guards`: indexed as the scene numbers them.
  FlightSettings(const scenario::Scenario& s, const std::vector<scenario::GuardSpec>& guards);
};

}  // namespace j232::flight
