#pragma once
// What a parameter study can vary (report 445-1, Appendix A, first program, and its
// Figs 2.8-2.16), and how each lands on an impact case or a J232 scenario:
//
//   blade_speed      "1000 rpm"  the blade's angular speed
//   blade_mass       "22 lb"     every blade mass (hub bar, links, their inertias and the
//                                hub's extra inertia) scaled so the blade weighs this;
//                                the drive line is not part of the blade and is kept
//   restitution      0.9         nail-on-blade (object-on-blade) coefficient, constant
//   contact_radius   "22 in"     impact: where the blade strikes; J232: the feed stations'
//                                radius (where nails are dropped)
//   pivot_position   0.5         S/L: pivot distance from the tip circle over the tip
//                                radius, for a blade of one hub bar and one link per arm,
//                                of uniform mass per length (report Fig 2.16); the tip
//                                radius and the blade's mass are kept
//   object_mass      "2 g"       impact: the object; J232: the nail
//   object_speed     "440 ft/min" impact only: the object's speed toward the blade
//   bevel_angle      "30 deg"    J232 only: every blade edge's bevel (a deck's blades alike)
//   edge_friction    0.4         J232 only: nail-on-blade Coulomb friction, every blade
//   sail_height      "20 mm"     J232 only: every blade's sail (0: none)
//   cut_height       "4 in"      field only: the lowest blade's mid-plane above the turf, the
//                                mower set to it as its wheels set it: every blade, the deck, its
//                                skirt, openings, chutes, guards and deflectors move up or down
//                                together; the ground and the field stay (a generated deck only)
// (`lift_angle`, a tilt of the contact normal in earlier versions, is refused: the lift
// now follows from the edge's geometry and friction.)
//
// Any other name is a dotted key of the base file itself (`housing.guards.openness`),
// set before the file is read, so every input can be swept.
#include <optional>
#include <string>
#include <toml++/toml.h>

#include "scenario/impact_input.hpp"
#include "scenario/scenario.hpp"
#include "units/quantity.hpp"

namespace j232::study {

enum class Parameter { BladeSpeed, BladeMass, Restitution, ContactRadius, PivotPosition, ObjectMass, ObjectSpeed, BevelAngle, EdgeFriction, SailHeight, CutHeight, FileKey };

struct ParameterInfo {
  Parameter parameter;
  std::string name;        // as written
  units::Kind kind;        // for named parameters
  std::string axis_title;  // "blade speed (rpm)"
  double display_factor;   // SI value / factor = the number on the axis
};

// Named parameters, or FileKey for anything else.
ParameterInfo parameter_info(const std::string& name);

// One value of a parameter: as the user wrote it (for labels) and in SI (named) or as
// TOML text (file keys).
struct Setting {
  ParameterInfo info;
  std::string text;  // "700 rpm"
  double si = 0;     // SI value (named parameters; file keys when the text is a number or quantity)
};

// Parses `text` for the parameter; throws InputError naming `where` (file:line: key).
Setting make_setting(const ParameterInfo& info, const std::string& text, const std::string& file, std::optional<int> line,
                     const std::string& key);

// File keys go into the document before it is read; named parameters onto the result.
void apply_to_document(const Setting& s, toml::table& document, const std::string& origin);
void apply(const Setting& s, scenario::ImpactCase& c);
void apply(const Setting& s, scenario::Scenario& sc);

// The mower set to cut at `height` (cut_height above); throws std::invalid_argument for a
// mesh deck, or a skirt, guard, deflector or blade that would go below the turf.
void set_cut_height(scenario::Scenario& sc, double height);
// The blade with its masses scaled to `mass` / re-split at pivot position `s_over_l`.
void scale_blade_mass(blade::Blade& b, double mass);
void set_pivot_position(blade::Blade& b, double s_over_l);

}  // namespace j232::study
