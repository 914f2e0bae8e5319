#include "assess/simulator.hpp"

#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "flight/launch.hpp"
#include "scenario/input_error.hpp"
#include "scene/j232_setup.hpp"
#include "strike/impulse.hpp"
#include "units/quantity.hpp"

namespace j232::assess {

using Vec3 = Eigen::Vector3d;


namespace {
// A field scenario has no test rig: it is assessed with `j232 hazard`.
const scenario::Scenario& test_rig(const scenario::Scenario& s) {
  if (s.field.present)
    throw scenario::InputError(s.file, std::nullopt, "field", "",
                               "this scenario describes a mower in a field ([field]), not the J232 test: run it with `j232 hazard`");
  return s;
}
}  // namespace

Simulator::Simulator(const scenario::Scenario& s, scene::Engine engine) : scenario_(test_rig(s)), spindles_(strike::scenario_spindles(s, s.restitution)) {
  mower_ = std::make_unique<flight::Mower>(scenario_, engine);
  context_ = mower_->context();
  context_.spindles = &spindles_;
  // A derived operator zone on a board with no zone mesh of its own.
  bool zone_mesh = false;
  for (const auto& m : s.meshes) zone_mesh |= m.label == scenario::MeshLabel::OperatorZone;
  if (s.zone.kind == scenario::OperatorZoneSpec::Kind::Derived && !zone_mesh) {
    zone_.emplace(s.zone, s.blade_plane());
    context_.zone = &*zone_;
  }
}

std::string Simulator::exit_name(flight::Exit exit, std::uint16_t index) const {
  switch (exit) {
    case flight::Exit::Inside: return "never left the deck";
    case flight::Exit::UnderSkirt: return "under the skirt";
    case flight::Exit::OverDeck: return "over the deck";
    case flight::Exit::DeckEdge: return "deck edge";
    case flight::Exit::Opening:
      return "opening: " + (index < scenario_.housing.openings.size() ? scenario_.housing.openings[index].name : std::string("?"));
    case flight::Exit::Guard: return "guard: " + (index < mower_->guards().size() ? mower_->guards()[index].name : std::string("?"));
  }
  return "unknown";
}

NailOutcome Simulator::simulate(std::uint64_t replicate, int nail) const { return run_nail(replicate, nail, nullptr); }

NailOutcome Simulator::trace(std::uint64_t replicate, int nail, std::vector<flight::Vec3>& path) const {
  path.clear();
  return run_nail(replicate, nail, &path);
}

NailReplay Simulator::replay(std::uint64_t replicate, int nail) const {
  NailReplay r;
  r.outcome = run_nail(replicate, nail, &r.path, &r);
  return r;
}

NailOutcome Simulator::run_nail(std::uint64_t replicate, int nail, std::vector<flight::Vec3>* path, NailReplay* replay) const {
  const scenario::Scenario& s = scenario_;
  NailOutcome out;
  out.flight.fate = flight::Fate::NotStruck;
  random::Stream feed_rng(s.run.seed, replicate, static_cast<std::uint64_t>(nail), random::Purpose::Feed);
  const feed::NailDrop drop = feed::sample_drop(s, nail, feed_rng);
  if (replay) replay->drop = drop;
  // The spindle this nail's station feeds strikes it (drop and strike are about its axis).
  const std::size_t k0 = drop.spindle;
  const strike::Spindle& spindle = spindles_[k0];
  const scenario::SpindleSpec& spec = s.spindles[k0];
  out.station = drop.station;
  out.spindle = static_cast<int>(k0);
  // The strike: the blade's first touch on the falling capsule, and its impulse.
  const feed::FallThrough fall = feed::fall_through(drop, spindle);
  strike::SearchStats search;
  auto contact = strike::first_contact(spindle, drop.blade_phase, drop.nail, fall.motion, fall.until, search,
                                       spindle.reference_search ? strike::SearchMethod::FixedSteps : strike::SearchMethod::Advancement);
  if (search.gave_up) {
    out.flight.fate = flight::Fate::CutOff;
    out.flight.cut_off = flight::CutOff::SearchSteps;
    return out;
  }
  if (!contact) return out;
  contact->spindle = k0;
  const Vec3 falling = fall.motion.velocity(contact->time);
  const flight::Launch struck = flight::launch(spindle, *contact, drop.nail, falling);
  if (replay)
    replay->strike = *contact, replay->falling = falling, replay->velocity_after = struck.hit.pushed_velocity(),
    replay->spin_after = struck.hit.pushed_spin();
  if (struck.result == flight::Launch::Result::NonFinite) {
    out.flight.fate = flight::Fate::CutOff;
    out.flight.cut_off = flight::CutOff::NonFinite;
    out.flight.non_finite = true;
    return out;
  }
  if (struck.result != flight::Launch::Result::Thrown) return out;  // not struck: the test did not happen for it
  const flight::Body& body = struck.body;
  flight::Drag drag;
  drag.on = s.air.drag;
  const projectile::Projectile& rod = drop.nail;
  drag.k_axial = s.air.density * s.air.cd_axial * (0.25 * units::pi * rod.diameter * rod.diameter) / (2 * rod.mass);
  drag.k_normal = s.air.density * s.air.cd_normal * (rod.length * rod.diameter) / (2 * rod.mass);
  drag.k_spin = 3 * s.air.density * s.air.cd_normal * rod.diameter * rod.length * rod.length / (16 * rod.mass);
  drag.air = {-s.feed.ground_speed, 0.0, 0.0};  // still air, seen from the moving mower
  drag.spin_average = s.air.spin_average;

  random::EventDraws flight_draws(s.run.seed, replicate, static_cast<std::uint64_t>(nail));
  // The other blades' angles at time 0: locked to the feeding one on a timed deck, else
  // independent and random (belt-driven spindles drift apart).
  strike::BladePhases phases;
  for (std::size_t k = 0; k < spindles_.size(); ++k) {
    const auto& other = s.spindles[k];
    if (k == k0)
      phases.at_zero[k] = drop.blade_phase;
    else if (other.phase && spec.phase)
      phases.at_zero[k] = drop.blade_phase - *spec.phase + *other.phase;
    else
      phases.at_zero[k] = units::two_pi * feed_rng.uniform();
  }
  flight::FlightContext context = context_;
  context.path = path;
  if (replay) replay->struck = true, context.events = &replay->events, context.stretches = &replay->stretches;
  out.flight = flight::fly(body, rod, drag, context, phases, {k0, contact->edge}, flight_draws);
  const Vec3& launch = out.flight.launch_velocity;
  out.exit_speed = launch.norm();
  out.launch_elevation = std::atan2(launch.z(), std::hypot(launch.x(), launch.y()));
  out.contact_radius = contact->radius;
  return out;
}

}  // namespace j232::assess
