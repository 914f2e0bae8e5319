#include "scenario/impact_input.hpp"

#include <cmath>
#include <fmt/format.h>

#include "scenario/blade_input.hpp"

namespace j232::scenario {

using units::Kind;

blade::Restitution read_restitution(const TableReader& t) {
  const std::string model = t.string_or("model", "constant", {"constant", "power_law"});
  blade::Restitution r;
  if (model == "constant") {
    r = blade::Restitution::constant(t.quantity("e", Kind::Dimensionless, Range::UnitInterval));
  } else {
    const blade::Restitution d = blade::Restitution::default_power_law();
    r = blade::Restitution::power_law(t.quantity_or("coefficient", Kind::Dimensionless, d.coefficient, Range::Positive),
                                      t.quantity_or("exponent", Kind::Dimensionless, d.exponent),
                                      t.quantity_or("maximum", Kind::Dimensionless, d.maximum, Range::UnitInterval),
                                      t.quantity_or("reference_speed", Kind::Speed, d.reference_speed, Range::Positive));
    if (r.exponent > 0.0) throw t.error("exponent", "expected zero or a negative number: e falls as speed rises");
  }
  t.refuse_unknown_keys();
  return r;
}

namespace {

blade::StruckObject read_object(const TableReader& t, std::string& name) {
  blade::StruckObject o;
  name = t.string_or("name", "object", {});
  o.mass = t.quantity("mass", Kind::Mass, Range::Positive);
  const bool scalar = t.has("speed_toward_blade");
  const bool vector = t.has("velocity");
  if (scalar && vector) throw t.error("velocity", "give either speed_toward_blade or [object.velocity], not both");
  if (!scalar && !vector)
    throw t.error("speed_toward_blade",
                  "missing; expected the object's speed toward the blade such as \"440 ft/min\" "
                  "(or an [object.velocity] table)");
  if (scalar) {
    // The report's convention: the object moves against the blade's motion.
    o.velocity = {0.0, -t.quantity("speed_toward_blade", Kind::Speed), 0.0};
    (void)t.table("velocity");  // asked for, so an error's list of known keys names it
  } else {
    (void)t.quantity_or("speed_toward_blade", Kind::Speed, 0.0);
    const TableReader v = *t.table("velocity");
    o.velocity = {v.quantity_or("radial", Kind::Speed, 0.0), v.quantity_or("tangential", Kind::Speed, 0.0),
                  v.quantity_or("vertical", Kind::Speed, 0.0)};
    v.refuse_unknown_keys();
  }
  if (auto rod = t.table("rod")) {
    blade::Rod r;
    r.length = rod->quantity("length", Kind::Length, Range::Positive);
    r.offset = rod->quantity_or("offset", Kind::Length, 0.0);
    if (std::abs(r.offset) > 0.5 * r.length)
      throw rod->error("offset", fmt::format("expected a contact point on the rod: |offset| <= half its length ({:g} m)", 0.5 * r.length));
    r.transverse_inertia = rod->quantity_or("inertia", Kind::Inertia, o.mass * r.length * r.length / 12.0, Range::Positive);
    r.axis = blade::Vec3::UnitZ();  // the falling nail stands upright
    rod->refuse_unknown_keys();
    o.rod = r;
  }
  t.refuse_unknown_keys();
  return o;
}

}  // namespace

ImpactCase read_impact_case(const toml::table& document, const std::string& file) {
  TableReader root(document, file, "");
  ImpactCase c;
  c.source = file;
  c.title = root.string_or("title", "", {});

  auto blade_table = root.table("blade");
  if (!blade_table) throw root.error("blade", "missing; expected a [blade] table");
  c.blade = read_blade(*blade_table);
  blade_table->refuse_unknown_keys();

  auto contact = root.table("contact");
  if (!contact) throw root.error("contact", "missing; expected a [contact] table with the contact radius");
  const long long arms = static_cast<long long>(c.blade.arms.size());
  c.arm = static_cast<std::size_t>(contact->integer_or("arm", 1, 1, std::max(1LL, arms)) - 1);
  c.radius = contact->quantity("radius", Kind::Length, Range::Positive);
  auto where = blade::locate(c.blade, c.arm, c.radius);
  if (!where)
    throw contact->error("radius", fmt::format("expected a radius on the blade: at most {:.4g} m ({:.4g} in) from the "
                                               "spindle along arm {}",
                                               c.blade.tip_radius(), c.blade.tip_radius() / units::inch, c.arm + 1));
  c.location = *where;
  contact->refuse_unknown_keys();

  auto object = root.table("object");
  if (!object) throw root.error("object", "missing; expected an [object] table with mass and speed");
  c.object = read_object(*object, c.object_name);

  auto restitution = root.table("restitution");
  if (!restitution) throw root.error("restitution", "missing; expected a [restitution] table, for example e = 0.9");
  c.restitution = read_restitution(*restitution);

  root.refuse_unknown_keys();
  return c;
}

}  // namespace j232::scenario
