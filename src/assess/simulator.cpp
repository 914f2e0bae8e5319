#include "assess/simulator.hpp"

#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "scenario/input_error.hpp"
#include "scene/j232_setup.hpp"
#include "units/quantity.hpp"

namespace j232::assess {

namespace {
std::vector<feed::Spindle> make_spindles(const scenario::Scenario& s) {
  try {
    return {feed::Spindle(s.blade, s.geometry, s.restitution)};
  } catch (const std::invalid_argument& e) {
    throw scenario::InputError(s.file, std::nullopt, "blade", "", e.what());
  }
}
}  // namespace

Simulator::Simulator(const scenario::Scenario& s)
    : scenario_(s), spindles_(make_spindles(s)) {
  try {
    scene_ = std::make_unique<scene::Scene>(scene::build_scene_soup(scenario_));
  } catch (const std::invalid_argument& e) {
    throw scenario::InputError(s.file, std::nullopt, s.meshes.empty() ? "housing" : "meshes", "", e.what());
  }
  // Numbered as the scene numbers them: mesh guards first, then the generated ones.
  for (const auto& m : s.meshes)
    if (m.label == "guard") guards_.push_back(m.guard);
  if (!scene::mesh_roles(s).housing) guards_.insert(guards_.end(), s.housing.guards.begin(), s.housing.guards.end());
  if (guards_.empty()) guards_.emplace_back();
  context_.scene = scene_.get();
  context_.scenario = &scenario_;
  context_.deck_radius = scene::mesh_roles(s).housing ? s.blade.tip_radius() + 0.05 : s.housing.deck_radius;
  context_.counted_height = s.counted_height();
  context_.escape_radius = scene::escape_radius(s, scene_->soup());
  context_.guards = &guards_;
  context_.spindles = &spindles_;
}

NailOutcome Simulator::simulate(std::uint64_t replicate, int nail) const {
  const scenario::Scenario& s = scenario_;
  NailOutcome out;
  out.flight.fate = flight::Fate::NotStruck;
  random::Stream feed_rng(s.run.seed, replicate, static_cast<std::uint64_t>(nail), random::Purpose::Feed);
  const feed::NailDrop drop = feed::sample_drop(s, nail, feed_rng);
  const auto strike = feed::find_strike(drop, spindles_.front().edges, s.blade.omega, s.geometry);
  if (!strike) return out;

  // The feeding spindle (the one blade of a [blade] scenario) strikes it.
  const feed::Spindle& spindle = spindles_.front();
  feed::BladeHit hit;
  hit.time = strike->time;
  hit.edge = strike->edge;
  hit.radius = strike->radius;
  hit.azimuth = strike->azimuth;
  feed::NailAtBlade struck;
  struck.mass = drop.mass;
  struck.length = drop.length;
  struck.velocity = strike->nail_velocity;
  struck.axis = drop.axis;
  struck.offset = strike->offset;
  const auto hit_outcome = feed::strike(spindle, hit, struck);
  if (!hit_outcome) return out;
  const blade::ContactOutcome& contact = *hit_outcome;
  if (!contact.velocity_after.allFinite() || !contact.spin_after.allFinite()) {
    out.flight.fate = flight::Fate::CutOff;
    out.flight.non_finite = true;
    return out;
  }

  flight::Body body;
  body.position = strike->contact_point - strike->offset * drop.axis;
  body.velocity = contact.velocity_after;
  body.spin = contact.spin_after;
  body.axis = drop.axis;
  body.time = strike->time;  // the blades' clock: re-strikes are timed against it
  flight::Drag drag;
  drag.on = s.air.drag;
  drag.k_axial = s.air.density * s.air.cd_axial * (0.25 * units::pi * drop.diameter * drop.diameter) / (2 * drop.mass);
  drag.k_normal = s.air.density * s.air.cd_normal * (drop.length * drop.diameter) / (2 * drop.mass);
  drag.air = {-s.feed.ground_speed, 0.0, 0.0};  // still air, seen from the moving mower

  random::Stream flight_rng(s.run.seed, replicate, static_cast<std::uint64_t>(nail), random::Purpose::Flight);
  feed::BladePhases phases;
  phases.at_zero[0] = drop.blade_phase;
  out.flight = flight::fly(body, drop.length, drop.diameter, drop.mass, drag, context_, phases, flight_rng);
  out.exit_speed = contact.velocity_after.norm();
  out.contact_radius = strike->radius;
  return out;
}

}  // namespace j232::assess
