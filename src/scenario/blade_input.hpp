#pragma once
// Reads the [blade] table of a scenario into a blade::Blade.
//
//   [blade]
//   speed = "1000 rpm"
//   [blade.hub]
//   bar_mass = "22 lb"        bar_length = "2 ft"     bar_mount = "end" | "centre"
//   inertia = "0 kg m^2"      drive_inertia = "0 kg m^2"   drive = "free" | "constant_speed"
//   [[blade.arms]]
//   azimuth = "0 deg"         pivot_radius = "5 in"   (default: the hub bar's reach)
//   [[blade.arms.links]]
//   length = "5 in"  mass = "85 g"  centre_of_mass = "2.5 in"  inertia = "..."  seized = false
#include "blade/blade.hpp"
#include "scenario/toml_reader.hpp"

namespace j232::scenario {

// Reads speed, hub and arms. The caller may read further keys of the same table
// (the assessment's blade height, thickness, lift) and then refuses unknown ones.
blade::Blade read_blade(const TableReader& blade_table);

}  // namespace j232::scenario
