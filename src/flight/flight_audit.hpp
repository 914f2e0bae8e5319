#pragma once
// The audit of a replayed flight (`j232 trace --check`, and the tests over every shipped
// scenario): along every stretch of its motion, at both ends and between, the capsule
// against every face of the scene (scene/capsule_audit.hpp: brute force, CGAL's distances,
// nothing of the contact search it checks), and every bounce's energy.
#include <vector>

#include "flight/nail_flight.hpp"

namespace j232::flight {

inline constexpr double kAuditOverlap = 1e-4;  // m: the most a capsule may reach into a face (the acceptance bound)

struct FlightAudit {
  long poses = 0;                 // poses checked
  double deepest = -HUGE_VAL;     // m, the deepest overlap found (<= 0: clear everywhere)
  double deepest_time = 0;        // s, when
  std::uint32_t deepest_face = 0;
  scene::Surface deepest_label = scene::Surface::Ground;
  int energy_gains = 0;           // bounces (or falls flat) that created energy
  double largest_gain = 0;        // J
  double placed_depth = 0;        // m, the deepest it started in a face it was placed in (as_placed)
  bool passed() const { return deepest <= kAuditOverlap && energy_gains == 0; }
  void merge(const FlightAudit& o);
};

// `samples`: poses checked inside each stretch besides its two ends. `as_placed`: the object
// was placed where it starts, and may stay in the faces it lies in there as deep as it started
// (a field's stone pressed into the soil by its embedment, a chain curtain draped over it),
// plus the search's slack; a nail starts at the blade and has no such allowance.
FlightAudit audit_flight(const scene::Soup& soup, const projectile::Projectile& nail, const std::vector<FlightStretch>& stretches,
                         const std::vector<FlightEvent>& events, int samples = 8, bool as_placed = false);

}  // namespace j232::flight
