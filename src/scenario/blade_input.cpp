#include "scenario/blade_input.hpp"

#include <fmt/format.h>

#include <cmath>

namespace j232::scenario {

using units::Kind;

namespace {

// Plausibility limits for any rotary cutter blade, the report's lab rigs included (its
// Figs 2.8-2.15 strike objects up to the blade's own 22 lb): generous, but they refuse a
// slip of unit ("24 km") before it becomes a meaningless simulation.
constexpr double kMaxLength = 3.0;      // m, one link or a pivot radius
constexpr double kMaxMass = 500.0;      // kg
constexpr double kMaxInertia = 1000.0;  // kg m^2
constexpr double kMaxSpeed = 20000 * units::rpm;

blade::Link read_link(const TableReader& t) {
  blade::Link link;
  link.length = t.quantity("length", Kind::Length, Range::positive_up_to(kMaxLength));
  link.mass = t.quantity("mass", Kind::Mass, Range::positive_up_to(kMaxMass));
  link.centre_of_mass = t.optional_quantity("centre_of_mass", Kind::Length, Range::NonNegative);
  if (link.centre_of_mass && *link.centre_of_mass > link.length)
    throw t.error("centre_of_mass", fmt::format("expected a distance from the inner pin within the link's length ({} m)", link.length));
  link.inertia_about_centre = t.optional_quantity("inertia", Kind::Inertia, Range::between(0, kMaxInertia));
  // A link's mass lies within about its length of its centre (a knife is longer than it is
  // wide), so its inertia about its centre is below m L^2; and above zero (it has extent).
  if (link.inertia_about_centre && !(*link.inertia_about_centre > 0 && *link.inertia_about_centre <= link.mass * link.length * link.length))
    throw t.error("inertia", fmt::format("expected an inertia about the link's centre above 0 and at most its mass times its length "
                                         "squared ({:.4g} kg m^2): no part of a {:.4g} m link lies farther than that from its centre",
                                         link.mass * link.length * link.length, link.length));
  link.seized = t.boolean_or("seized", false);
  t.refuse_unknown_keys();
  return link;
}

}  // namespace

blade::Blade read_blade(const TableReader& t) {
  blade::Blade b;
  b.omega = t.quantity("speed", Kind::AngularSpeed, Range::positive_up_to(kMaxSpeed));

  if (auto hub = t.table("hub")) {
    b.hub.bar_mass = hub->quantity_or("bar_mass", Kind::Mass, 0.0, Range::between(0, kMaxMass));
    b.hub.bar_length = hub->quantity_or("bar_length", Kind::Length, 0.0, Range::between(0, 2 * kMaxLength));
    if ((b.hub.bar_mass > 0.0) != (b.hub.bar_length > 0.0))
      throw hub->error(b.hub.bar_mass > 0.0 ? "bar_length" : "bar_mass", "a hub bar needs both bar_mass and bar_length (or neither)");
    b.hub.bar_mount = hub->string_or("bar_mount", "centre", {"centre", "end"}) == "end" ? blade::BarMount::End : blade::BarMount::Centre;
    b.hub.extra_inertia = hub->quantity_or("inertia", Kind::Inertia, 0.0, Range::between(0, kMaxInertia));
    b.hub.drive_inertia = hub->quantity_or("drive_inertia", Kind::Inertia, 0.0, Range::between(0, kMaxInertia));
    b.hub.constant_speed = hub->string_or("drive", "free", {"free", "constant_speed"}) == "constant_speed";
    hub->refuse_unknown_keys();
  }

  for (const TableReader& a : t.array_of_tables("arms", 16)) {
    blade::Arm arm;
    arm.azimuth = a.quantity_or("azimuth", Kind::Angle, 0.0, Range::between(-4 * units::pi, 4 * units::pi));
    arm.pivot_radius = a.quantity_or("pivot_radius", Kind::Length, b.hub.reach(), Range::between(0, kMaxLength));
    for (const TableReader& l : a.array_of_tables("links", 16)) arm.links.push_back(read_link(l));
    if (arm.links.empty()) throw a.error("links", "an arm needs at least one [[blade.arms.links]] table");
    // Two arms pinned at one point would be two knives in one place.
    for (const auto& other : b.arms) {
      const double apart = std::abs(std::remainder(arm.azimuth - other.azimuth, 2 * units::pi));
      if (apart < 1e-9 && std::abs(arm.pivot_radius - other.pivot_radius) < 1e-9)
        throw a.error("azimuth", fmt::format("puts this arm's pivot where an earlier arm's is ({:g} deg, {:g} m from the spindle): two "
                                             "knives cannot hang from one pin; expected another azimuth",
                                             arm.azimuth / units::degree, arm.pivot_radius));
    }
    a.refuse_unknown_keys();
    b.arms.push_back(std::move(arm));
  }

  if (!b.hub.constant_speed && b.hub.inertia() <= 0.0 && b.arms.empty())
    throw t.error("hub",
                  "the blade has no inertia: give [blade.hub] a bar_mass and bar_length or an inertia, "
                  "or add [[blade.arms]]");
  return b;
}

}  // namespace j232::scenario
