#include "scenario/blade_input.hpp"

#include <fmt/format.h>

namespace j232::scenario {

using units::Kind;

namespace {

blade::Link read_link(const TableReader& t) {
  blade::Link link;
  link.length = t.quantity("length", Kind::Length, Range::Positive);
  link.mass = t.quantity("mass", Kind::Mass, Range::Positive);
  link.centre_of_mass = t.optional_quantity("centre_of_mass", Kind::Length, Range::NonNegative);
  if (link.centre_of_mass && *link.centre_of_mass > link.length)
    throw t.error("centre_of_mass", fmt::format("expected a distance from the inner pin within the link's length ({} m)",
                                                link.length));
  link.inertia_about_centre = t.optional_quantity("inertia", Kind::Inertia, Range::NonNegative);
  link.seized = t.boolean_or("seized", false);
  t.refuse_unknown_keys();
  return link;
}

}  // namespace

blade::Blade read_blade(const TableReader& t) {
  blade::Blade b;
  b.omega = t.quantity("speed", Kind::AngularSpeed, Range::Positive);

  if (auto hub = t.table("hub")) {
    b.hub.bar_mass = hub->quantity_or("bar_mass", Kind::Mass, 0.0, Range::NonNegative);
    b.hub.bar_length = hub->quantity_or("bar_length", Kind::Length, 0.0, Range::NonNegative);
    if ((b.hub.bar_mass > 0.0) != (b.hub.bar_length > 0.0))
      throw hub->error(b.hub.bar_mass > 0.0 ? "bar_length" : "bar_mass",
                       "a hub bar needs both bar_mass and bar_length (or neither)");
    b.hub.bar_mount = hub->string_or("bar_mount", "centre", {"centre", "end"}) == "end" ? blade::BarMount::End
                                                                                       : blade::BarMount::Centre;
    b.hub.extra_inertia = hub->quantity_or("inertia", Kind::Inertia, 0.0, Range::NonNegative);
    b.hub.drive_inertia = hub->quantity_or("drive_inertia", Kind::Inertia, 0.0, Range::NonNegative);
    b.hub.constant_speed = hub->string_or("drive", "free", {"free", "constant_speed"}) == "constant_speed";
    hub->refuse_unknown_keys();
  }

  for (const TableReader& a : t.array_of_tables("arms")) {
    blade::Arm arm;
    arm.azimuth = a.quantity_or("azimuth", Kind::Angle, 0.0);
    arm.pivot_radius = a.quantity_or("pivot_radius", Kind::Length, b.hub.reach(), Range::NonNegative);
    for (const TableReader& l : a.array_of_tables("links")) arm.links.push_back(read_link(l));
    if (arm.links.empty()) throw a.error("links", "an arm needs at least one [[blade.arms.links]] table");
    a.refuse_unknown_keys();
    b.arms.push_back(std::move(arm));
  }

  if (!b.hub.constant_speed && b.hub.inertia() <= 0.0 && b.arms.empty())
    throw t.error("hub", "the blade has no inertia: give [blade.hub] a bar_mass and bar_length or an inertia, "
                         "or add [[blade.arms]]");
  return b;
}

}  // namespace j232::scenario
