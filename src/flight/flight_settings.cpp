#include "flight/flight_settings.hpp"

namespace j232::flight {

FlightSettings::FlightSettings(const scenario::Scenario& s, const std::vector<scenario::GuardSpec>& guards)
    : chord_tolerance(s.run.chord_tolerance),
      time_limit(s.time_limit()),
      max_bounces(s.max_bounces()),
      max_gentle_contacts(s.run.max_gentle_contacts),
      max_strikes(s.max_strikes()),
      max_contacts_per_pass(s.run.max_contacts_per_pass),
      rest_speed(s.run.rest_speed),
      law(s.run.restitution_law),
      contacts(s.run.contact_model),
      blade_push(s.run.blade_push),
      board(s.board),
      materials(s, guards) {
  for (const auto& o : s.housing.openings) openings.push_back({o.azimuth, s.housing.opening_top(o)});
}

}  // namespace j232::flight
