// The impact calculator's input: good files read correctly whatever units they use,
// bad ones are refused naming the file, line, key, value and what was expected.
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <string>

#include "blade/blade_model.hpp"
#include "scenario/impact_input.hpp"

using namespace j232;
using Catch::Contains;

namespace {

scenario::ImpactCase read(const std::string& text) {
  return scenario::read_impact_case(toml::parse(std::string_view(text), std::string_view("case.toml")), "case.toml");
}

const std::string kPivotedSI = R"(
title = "pivoted, SI"
[blade]
speed = "104.71975511965977 rad/s"
[blade.hub]
bar_mass = "4.98951607 kg"
bar_length = "0.3048 m"
bar_mount = "end"
drive_inertia = "0.0421401100938048 kg m^2"
[[blade.arms]]
pivot_radius = "0.3048 m"
[[blade.arms.links]]
length = "0.3048 m"
mass = "4.98951607 kg"
[contact]
radius = "0.5588 m"
[object]
mass = "0.00226796185 kg"
speed_toward_blade = "2.2352 m/s"
[object.rod]
length = "0.0508 m"
offset = "0.01 m"
[restitution]
e = 0.9
)";

const std::string kPivotedImperial = R"(
title = "pivoted, customary units"
[blade]
speed = "1000 rpm"
[blade.hub]
bar_mass = "11 lb"
bar_length = "1 ft"
bar_mount = "end"
drive_inertia = "1 lb ft^2"
[[blade.arms]]
pivot_radius = "12 in"
[[blade.arms.links]]
length = "12 in"
mass = "176 oz"
[contact]
radius = "22 in"
[object]
mass = "0.005 lb"
speed_toward_blade = "5 mph"
[object.rod]
length = "2 in"
offset = "10 mm"
[restitution]
e = "90 %"
)";

// Replaces the first occurrence of `from` in the base case.
std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("impact input: results do not depend on the units of the input", "[input]") {
  const auto si = read(kPivotedSI), imperial = read(kPivotedImperial);
  const auto a = blade::solve_impact(blade::BladeModel(si.blade), si.location, si.object, si.restitution);
  const auto b = blade::solve_impact(blade::BladeModel(imperial.blade), imperial.location, imperial.object, imperial.restitution);
  const auto& c = a;
  CHECK(c.contact.velocity_after.y() == Approx(b.contact.velocity_after.y()).epsilon(1e-12));
  CHECK(c.contact.spin_after.x() == Approx(b.contact.spin_after.x()).epsilon(1e-12));
  CHECK(c.hub_rate_after == Approx(b.hub_rate_after).epsilon(1e-12));
  CHECK(c.link_rates[0][0] == Approx(b.link_rates[0][0]).epsilon(1e-12));
  CHECK(c.contact.energy_lost == Approx(b.contact.energy_lost).epsilon(1e-12));
}

TEST_CASE("impact input: the contact radius picks the body it falls on", "[input]") {
  const auto hub = read(with(kPivotedSI, "radius = \"0.5588 m\"", "radius = \"0.2 m\""));
  CHECK(hub.location.on_hub);
  const auto link = read(kPivotedSI);
  CHECK_FALSE(link.location.on_hub);
  CHECK(link.location.link == 0);
  CHECK(link.location.distance == Approx(0.5588 - 0.3048));
}

TEST_CASE("impact input: bad input is refused with file, line, key, value and expectation", "[input][errors]") {
  struct Bad {
    std::string from, to, message;
  };
  const Bad cases[] = {
      {"bar_mass = \"4.98951607 kg\"", "bar_mass = \"-3 kg\"",
       "case.toml:6: blade.hub.bar_mass = \"-3 kg\": expected a mass such as \"22 lb\" or \"170 g\", from 0 kg to 500 kg"},
      {"\nmass = \"4.98951607 kg\"", "\nmass = \"-1 kg\"",
       "case.toml:14: blade.arms[1].links[1].mass = \"-1 kg\": expected a mass such as \"22 lb\" or \"170 g\", above 0 kg and at most 500 "
       "kg"},
      {"e = 0.9", "e = 1.2", "case.toml:24: restitution.e = 1.2: expected a plain number such as 0.9, from 0 to 1"},
      {"e = 0.9", "e = -0.1", "restitution.e = -0.1"},
      {"radius = \"0.5588 m\"", "radius = \"0.7 m\"",
       "case.toml:16: contact.radius = \"0.7 m\": expected a radius on the blade: at most 0.6096 m"},
      {"speed = \"104.71975511965977 rad/s\"", "speed = \"1000 rpms\"", "blade.speed = \"1000 rpms\": unknown unit \"rpms\""},
      {"speed = \"104.71975511965977 rad/s\"", "speed = \"1000\"", "blade.speed = \"1000\": \"1000\" has no unit"},
      {"speed = \"104.71975511965977 rad/s\"", "speed = 1000", "blade.speed = 1000: a number needs a unit here"},
      {"mass = \"0.00226796185 kg\"", "mass = \"2 in\"", "object.mass = \"2 in\": \"2 in\" has the wrong kind of unit; expected a mass"},
      {"[contact]\n", "[contact]\nradius2 = 3\n", "case.toml:16: contact.radius2: unknown key; this table takes:"},
      {"bar_mount = \"end\"", "bar_mount = \"middle\"", "blade.hub.bar_mount = \"middle\": expected one of \"centre\", \"end\""},
      {"offset = \"0.01 m\"", "offset = \"0.04 m\"", "object.rod.offset = \"0.04 m\": expected a contact point on the rod"},
      {"[restitution]\ne = 0.9", "[restitution]\nmodel = \"power_law\"\nexponent = 0.5", "restitution.exponent = 0.5"},
      {"speed_toward_blade = \"2.2352 m/s\"", "", "object.speed_toward_blade: missing"},
      {"[[blade.arms.links]]\nlength = \"0.3048 m\"\nmass = \"4.98951607 kg\"\n", "", "blade.arms[1].links: an arm needs at least one"},
  };
  for (const auto& c : cases) {
    INFO("changing «" << c.from << "» to «" << c.to << "»");
    CHECK_THROWS_WITH(read(with(kPivotedSI, c.from, c.to)), Contains(c.message));
  }
  CHECK_THROWS_WITH(read("[blade]\nspeed = \"1 rpm\"\n"), Contains("blade.hub: the blade has no inertia"));
  CHECK_THROWS_WITH(read("x = 1\n"), Contains("blade: missing"));
  CHECK_THROWS_WITH(scenario::parse_toml_file("/nonexistent/impact.toml"), Contains("/nonexistent/impact.toml: no such file"));
}

TEST_CASE("impact input: malformed TOML is refused with its file and line", "[input][errors]") {
  const std::string path = "impact-input-malformed.toml";
  {
    std::ofstream out(path);
    out << with(kPivotedSI, "[contact]", "[blade]");
  }
  CHECK_THROWS_WITH(scenario::parse_toml_file(path),
                    Contains("impact-input-malformed.toml:15: not valid TOML") && Contains("cannot redefine existing table 'blade'"));
  std::remove(path.c_str());
}
