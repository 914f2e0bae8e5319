#pragma once
// The single-impact calculator's input (report 445-1, Appendix A, second program):
// a blade, where it is struck, the struck object and the restitution law.
//
//   title = "..."
//   [blade] ...                          (see blade_input.hpp)
//   [contact]  arm = 1   radius = "9.5 in"
//   [object]   name = "..."  mass = "19 g"  speed_toward_blade = "88 ft/min"
//              or [object.velocity] tangential = "..."  radial = "..."  vertical = "..."
//   [object.rod]  length = "2 in"  offset = "0.5 in"  inertia = "..."   (eccentric impact)
//   [restitution] e = 0.9
//              or model = "power_law"  coefficient = 1.06  exponent = -0.25  maximum = 0.9
//                 reference_speed = "1 m/s"
#include <string>
#include <toml++/toml.h>

#include "blade/blade_model.hpp"
#include "blade/impact.hpp"
#include "scenario/toml_reader.hpp"

namespace j232::scenario {

struct ImpactCase {
  std::string source;  // file it came from, or "command line"
  std::string title;
  std::string object_name;
  blade::Blade blade;
  std::size_t arm = 0;  // 0-based
  double radius = 0.0;  // m from the spindle
  blade::ContactLocation location;
  blade::StruckObject object;  // velocity in the struck arm's frame: x radial, y tangential, z up
  blade::Restitution restitution;
};

// Reads and checks an impact case from a parsed document. Throws InputError.
ImpactCase read_impact_case(const toml::table& document, const std::string& file);

// Restitution from a [restitution] table (shared with the Monte Carlo scenario).
blade::Restitution read_restitution(const TableReader& table);

}  // namespace j232::scenario
