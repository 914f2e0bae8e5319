#include "study/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "pipeline/pipeline.hpp"
#include "scenario/input_error.hpp"
#include "scenario/toml_override.hpp"

namespace j232::study {

using units::Kind;

ParameterInfo parameter_info(const std::string& name) {
  if (name == "blade_speed") return {Parameter::BladeSpeed, name, Kind::AngularSpeed, "blade speed (rpm)", units::rpm};
  if (name == "blade_mass") return {Parameter::BladeMass, name, Kind::Mass, "blade mass (kg)", 1.0};
  if (name == "restitution") return {Parameter::Restitution, name, Kind::Dimensionless, "coefficient of restitution e", 1.0};
  if (name == "contact_radius") return {Parameter::ContactRadius, name, Kind::Length, "contact radius (m)", 1.0};
  if (name == "pivot_position") return {Parameter::PivotPosition, name, Kind::Dimensionless, "pivot position S/L", 1.0};
  if (name == "object_mass") return {Parameter::ObjectMass, name, Kind::Mass, "object mass (kg)", 1.0};
  if (name == "bevel_angle") return {Parameter::BevelAngle, name, Kind::Angle, "edge bevel angle (deg)", units::degree};
  if (name == "edge_friction") return {Parameter::EdgeFriction, name, Kind::Dimensionless, "nail-on-blade friction", 1.0};
  if (name == "sail_height") return {Parameter::SailHeight, name, Kind::Length, "sail height (mm)", 0.001};
  if (name == "cut_height") return {Parameter::CutHeight, name, Kind::Length, "cut height (in)", units::inch};
  if (name == "object_speed") return {Parameter::ObjectSpeed, name, Kind::Speed, "object speed toward the blade (m/s)", 1.0};
  return {Parameter::FileKey, name, Kind::Dimensionless, name, 1.0};
}

namespace {
// The SI unit a file key's values were converted to, for the axis title.
std::string si_unit(const units::Dimension& d) {
  using D = units::Dimension;
  if (d == D{0, 1, 0, 0}) return "m";
  if (d == D{1, 0, 0, 0}) return "kg";
  if (d == D{0, 0, 1, 0}) return "s";
  if (d == D{0, 1, -1, 0}) return "m/s";
  if (d == D{0, 0, -1, 1}) return "rad/s";
  if (d == D{0, 0, 0, 1}) return "rad";
  return "SI units";
}

// The heights a deck's openings and curtains take from the deck plate when the file leaves
// them out, written in: a parameter that moves the deck (cut height) then moves them with it
// as it moves written ones, and one that reshapes it elsewhere leaves them where they were.
void materialise_housing_heights(scenario::HousingSpec& h) {
  for (auto& op : h.openings) op.chute_end_top = h.chute_end_top(op), op.top = h.opening_top(op);
  for (auto& g : h.guards)
    if (!g.along.empty()) g.top = h.guard_top(g);
}
}  // namespace

Setting make_setting(const ParameterInfo& info, const std::string& text, const std::string& file, std::optional<int> line,
                     const std::string& key) {
  Setting s{info, text, 0.0};
  const auto refuse = [&](const std::string& expected) { return scenario::InputError(file, line, key, text, expected); };
  if (info.name == "lift_angle")
    throw refuse(
        "lift_angle is no longer a parameter: the lift follows from the blade edge's geometry and friction; vary bevel_angle, "
        "edge_friction or sail_height (or a [blade.edge] key) instead");
  if (info.parameter == Parameter::FileKey) {
    // A number or quantity gives the chart a numeric axis (SI); anything else is still set.
    try {
      std::size_t used = 0;
      const double number = std::stod(text, &used);
      const std::string unit = text.substr(used);
      if (unit.find_first_not_of(' ') == std::string::npos) {
        s.si = number;
      } else {
        const auto u = units::parse_unit(unit.substr(unit.find_first_not_of(' ')));
        s.si = number * u.factor;
        s.info.axis_title = fmt::format("{} ({})", info.name, si_unit(u.dimension));
      }
    } catch (const std::exception&) {
      s.si = 0;
    }
    return s;
  }
  try {
    s.si = units::parse(text, info.kind);
  } catch (const units::UnitError& e) {
    throw refuse(fmt::format("{} ({}: expected {})", e.what(), info.name, units::describe(info.kind)));
  }
  switch (info.parameter) {
    case Parameter::Restitution:
      if (s.si < 0 || s.si > 1) throw refuse("expected a coefficient of restitution between 0 and 1");
      break;
    case Parameter::PivotPosition:
      if (s.si <= 0 || s.si >= 1) throw refuse("expected S/L strictly between 0 and 1");
      break;
    case Parameter::BevelAngle:
      if (s.si < 5 * units::degree || s.si > 90 * units::degree) throw refuse("expected a bevel angle from 5 deg to 90 deg");
      break;
    case Parameter::EdgeFriction:
      if (s.si < 0 || s.si > 2) throw refuse("expected a friction coefficient from 0 to 2");
      break;
    case Parameter::SailHeight:
      if (s.si < 0 || s.si > 0.2) throw refuse("expected a sail height from 0 to 200 mm");
      break;
    case Parameter::CutHeight:
      if (!(s.si > 0) || s.si > 1) throw refuse("expected a cut height above 0 and up to 1 m");
      break;
    default:
      if (!(s.si > 0)) throw refuse(fmt::format("expected a positive {}", units::describe(info.kind)));
  }
  return s;
}

void apply_to_document(const Setting& s, toml::table& document, const std::string& origin) {
  if (s.info.parameter == Parameter::FileKey) scenario::set_key(document, s.info.name, s.text, origin);
}

void scale_blade_mass(blade::Blade& b, double mass) {
  const double old = b.mass();
  if (!(old > 0)) throw std::invalid_argument("blade_mass: the base blade has no mass to scale");
  const double f = mass / old;
  b.hub.bar_mass *= f;
  b.hub.extra_inertia *= f;
  for (auto& arm : b.arms)
    for (auto& link : arm.links) {
      link.mass *= f;
      if (link.inertia_about_centre) *link.inertia_about_centre *= f;
    }
}

void set_pivot_position(blade::Blade& b, double s_over_l) {
  for (const auto& arm : b.arms)
    if (arm.links.size() != 1 || std::abs(arm.pivot_radius - b.hub.reach()) > 1e-9)
      throw std::invalid_argument("pivot_position: expected a blade of one hub bar and one link per arm, pinned at the bar's end");
  if (b.arms.empty()) throw std::invalid_argument("pivot_position: the base blade has no pivoted arm");
  const double tip = b.tip_radius(), mass = b.mass();
  const double bar_share = b.hub.bar_mount == blade::BarMount::End ? 1.0 : 2.0;  // bar lengths per unit reach
  const double pivot = tip * (1.0 - s_over_l), link = tip * s_over_l;
  // Uniform mass per length over the bar and the links.
  const double length = bar_share * pivot + link * static_cast<double>(b.arms.size());
  const double per_length = mass / length;
  b.hub.bar_length = bar_share * pivot;
  b.hub.bar_mass = per_length * b.hub.bar_length;
  for (auto& arm : b.arms) {
    arm.pivot_radius = pivot;
    auto& l = arm.links.front();
    l.length = link;
    l.mass = per_length * link;
    l.centre_of_mass.reset();
    l.inertia_about_centre.reset();
  }
}

void apply(const Setting& s, scenario::ImpactCase& c) {
  switch (s.info.parameter) {
    case Parameter::BladeSpeed: c.blade.omega = s.si; break;
    case Parameter::BladeMass: scale_blade_mass(c.blade, s.si); break;
    case Parameter::Restitution: c.restitution = blade::Restitution::constant(s.si); break;
    case Parameter::ContactRadius: c.radius = s.si; break;
    case Parameter::PivotPosition: set_pivot_position(c.blade, s.si); break;
    case Parameter::ObjectMass:
      if (c.object.rod) c.object.rod->transverse_inertia *= s.si / c.object.mass;
      c.object.mass = s.si;
      break;
    case Parameter::ObjectSpeed: c.object.velocity = {0.0, -s.si, 0.0}; break;
    case Parameter::BevelAngle:
    case Parameter::EdgeFriction:
    case Parameter::SailHeight:
      throw std::invalid_argument(s.info.name + ": an impact case has no blade edge geometry; it is a J232 parameter");
    case Parameter::CutHeight: throw std::invalid_argument("cut_height: an impact case has no deck or ground; it is a J232 or field parameter");
    case Parameter::FileKey: break;
  }
}

// Blade parameters apply to every spindle's blade (a deck of several is swept as one).
void apply(const Setting& s, scenario::Scenario& sc) {
  // What the parameter cannot mean for this scenario's pipeline (a field's objects have no feed radius).
  if (s.info.parameter != Parameter::FileKey)
    if (const std::string why = pipeline::pipeline_of(sc).refuse_parameter(s.info.name, sc); !why.empty()) throw std::invalid_argument(why);
  // The feed stations and the board's top stay where the file put them: a blade reshaped here
  // (a pivot moved, a mass scaled) may land its tip an ulp away, which must not move them.
  if (!sc.feed.stations) sc.feed.stations = sc.feed_stations();
  if (!sc.target.top) sc.target.top = sc.target_top();
  materialise_housing_heights(sc.housing);
  switch (s.info.parameter) {
    case Parameter::BladeSpeed:
      for (auto& sp : sc.spindles) sp.blade.omega = s.si;
      break;
    case Parameter::BladeMass:
      for (auto& sp : sc.spindles) scale_blade_mass(sp.blade, s.si);
      break;
    case Parameter::Restitution:
      sc.restitution = blade::Restitution::constant(s.si);
      break;
    case Parameter::ContactRadius:
      for (auto& f : *sc.feed.stations) f.radius = s.si;
      break;
    case Parameter::PivotPosition:
      for (auto& sp : sc.spindles) set_pivot_position(sp.blade, s.si);
      break;
    case Parameter::ObjectMass:
      sc.nail.mass = s.si;
      break;
    case Parameter::ObjectSpeed: throw std::invalid_argument("object_speed: no scenario throws its objects at the blade at a set speed");  // (each pipeline says why above)
    case Parameter::BevelAngle:
      for (auto& sp : sc.spindles) sp.geometry.edge.bevel_angle = s.si;
      break;
    case Parameter::EdgeFriction:
      for (auto& sp : sc.spindles) sp.geometry.edge.friction = s.si;
      break;
    case Parameter::SailHeight:
      for (auto& sp : sc.spindles) sp.geometry.edge.sail_height = s.si;
      break;
    case Parameter::CutHeight: set_cut_height(sc, s.si); break;
    case Parameter::FileKey: break;
  }
}

void set_cut_height(scenario::Scenario& sc, double height) {
  if (const std::string why = pipeline::pipeline_of(sc).refuse_parameter("cut_height", sc); !why.empty()) throw std::invalid_argument(why);
  if (!sc.meshes.empty())
    throw std::invalid_argument("cut_height: a deck from meshes cannot be moved; sweep the blades' height key and the meshes' files instead");
  double lowest = HUGE_VAL;
  for (const auto& sp : sc.spindles) lowest = std::min(lowest, sp.geometry.height);
  const double shift = height - lowest;
  auto& h = sc.housing;
  for (auto& sp : sc.spindles) sp.geometry.height += shift;
  materialise_housing_heights(h);  // (before the deck moves: then each moves with it, as written ones do)
  h.skirt_bottom += shift;
  for (auto& op : h.openings) *op.top += shift, *op.chute_end_top += shift;
  for (auto& g : h.guards) {
    g.bottom += shift;
    if (!g.along.empty()) *g.top += shift;
  }
  for (auto& d : h.deflectors) d.bottom += shift, d.top += shift;
  // What hangs lowest may reach the turf (a guard's edge, a deflector's); the skirt's foot
  // and a blade's lower face must stay above it.
  const auto above_turf = [&](const char* what, double z, bool may_touch) {
    if (z < 0 || (!may_touch && z == 0))
      throw std::invalid_argument(fmt::format("cut_height {:.4g} in: {} would be {:.3g} mm {} the turf (the mower set {:.4g} in "
                                              "lower than its file's)",
                                              height / units::inch, what, std::abs(1e3 * z), z < 0 ? "below" : "on",
                                              -shift / units::inch));
  };
  above_turf("the skirt's foot", h.skirt_bottom, false);
  for (const auto& g : h.guards) above_turf("a guard's lower edge", g.bottom, true);
  for (const auto& d : h.deflectors) above_turf("a deflector's lower edge", d.bottom, true);
  for (const auto& sp : sc.spindles) above_turf("a blade's lower face", sp.geometry.height - 0.5 * sp.geometry.thickness, false);
}

}  // namespace j232::study
