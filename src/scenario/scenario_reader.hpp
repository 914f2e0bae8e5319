#pragma once
// Reading a scenario file (TOML) into the plain data of scenario/scenario.hpp. The only
// part of the scenario that knows the file format; the physics sees the Scenario alone.
#include <string>
#include <toml++/toml.h>

#include "scenario/scenario.hpp"

namespace j232::scenario {

// Reads and checks a scenario file. Throws InputError naming file, line, key, value.
Scenario read_scenario(const std::string& file);
// The same from a parsed document (with keys set from outside, as sweeps do); `file`
// names it in errors and anchors relative mesh paths.
Scenario read_scenario(const toml::table& document, const std::string& file);

}  // namespace j232::scenario
