#include "assess/simulator.hpp"

#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "scenario/input_error.hpp"
#include "scene/j232_setup.hpp"
#include "units/quantity.hpp"

namespace j232::assess {

namespace {
blade::BladeModel make_model(const scenario::Scenario& s) {
  try {
    return blade::BladeModel(s.blade);
  } catch (const std::invalid_argument& e) {
    throw scenario::InputError(s.file, std::nullopt, "blade", "", e.what());
  }
}
}  // namespace

Simulator::Simulator(const scenario::Scenario& s)
    : scenario_(s), model_(make_model(s)), edges_(feed::leading_edges(s.blade)) {
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
}

NailOutcome Simulator::simulate(std::uint64_t replicate, int nail) const {
  const scenario::Scenario& s = scenario_;
  NailOutcome out;
  out.flight.fate = flight::Fate::NotStruck;
  random::Stream feed_rng(s.run.seed, replicate, static_cast<std::uint64_t>(nail), random::Purpose::Feed);
  const feed::NailDrop drop = feed::sample_drop(s, nail, feed_rng);
  const auto strike = feed::find_strike(drop, edges_, s.blade.omega, s.geometry);
  if (!strike) return out;

  const feed::Edge& edge = edges_[strike->edge];
  const auto where = edge.arm ? blade::locate(s.blade, *edge.arm, strike->radius)
                              : std::optional<blade::ContactLocation>(blade::ContactLocation::hub(strike->radius));
  if (!where) return out;
  // The edge's lift tilts the contact normal up out of the blade plane.
  const double cos_lift = std::cos(s.geometry.lift_angle), sin_lift = std::sin(s.geometry.lift_angle);
  const blade::Vec3 tangent(-std::sin(strike->azimuth), std::cos(strike->azimuth), 0.0);
  blade::BladeAtContact at;
  at.normal = cos_lift * tangent + sin_lift * blade::Vec3::UnitZ();
  at.effective_mass = model_.effective_mass(*where) / (cos_lift * cos_lift);
  at.speed = s.blade.omega * strike->radius * cos_lift;

  blade::StruckObject nail_body;
  nail_body.mass = drop.mass;
  nail_body.velocity = strike->nail_velocity;
  blade::Rod rod;
  rod.length = drop.length;
  rod.transverse_inertia = drop.mass * drop.length * drop.length / 12.0;
  rod.axis = drop.axis;
  rod.offset = strike->offset;
  nail_body.rod = rod;
  const blade::ContactOutcome contact = blade::resolve_contact(at, nail_body, s.restitution);
  if (!contact.approaching) return out;
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
  flight::Drag drag;
  drag.on = s.air.drag;
  drag.k_axial = s.air.density * s.air.cd_axial * (0.25 * units::pi * drop.diameter * drop.diameter) / (2 * drop.mass);
  drag.k_normal = s.air.density * s.air.cd_normal * (drop.length * drop.diameter) / (2 * drop.mass);
  drag.air = {-s.feed.ground_speed, 0.0, 0.0};  // still air, seen from the moving mower

  random::Stream flight_rng(s.run.seed, replicate, static_cast<std::uint64_t>(nail), random::Purpose::Flight);
  out.flight = flight::fly(body, drop.length, drop.diameter, drop.mass, drag, context_, flight_rng);
  out.exit_speed = contact.velocity_after.norm();
  out.contact_radius = strike->radius;
  return out;
}

}  // namespace j232::assess
