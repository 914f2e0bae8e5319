// A deck of several spindles: the scenario form, clockwise blades, and a whole run.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <toml++/toml.h>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "feed/feed.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario.hpp"
#include "scene/j232_setup.hpp"
#include "units/quantity.hpp"

using namespace j232;

namespace {
const std::string kBlades = R"(
[blades.bar]
speed = "2700 rpm"
[blades.bar.hub]
bar_mass = "3.5 lb"
bar_length = "25 in"
)";
const std::string kThree = kBlades + R"(
[[spindles]]
blade = "bar"
x = "0.2 m"
[[spindles]]
blade = "bar"
x = "-0.05 m"
y = "0.597 m"
sense = "cw"
phase = "30 deg"
[[spindles]]
blade = "bar"
x = "-0.05 m"
y = "-0.597 m"
phase = "0 deg"
)";

scenario::Scenario read(const std::string& text) {
  return scenario::read_scenario(toml::parse(text, std::string_view("deck.toml")), "deck.toml");
}
std::string scenario_path(const char* name) { return std::string(J232_SOURCE_DIR) + "/scenarios/" + name; }
}  // namespace

TEST_CASE("deck: [[spindles]] with named blades, positions, senses and phases", "[deck][input]") {
  const auto s = read(kThree);
  REQUIRE(s.spindles.size() == 3);
  CHECK(s.spindles[0].blade_name == "bar");
  CHECK(s.spindles[1].y == Approx(0.597));
  CHECK(s.spindles[1].sense == -1);
  CHECK(s.spindles[0].sense == +1);
  CHECK_FALSE(s.spindles[0].phase);  // untimed unless a phase is given
  CHECK(*s.spindles[1].phase == Approx(30 * units::pi / 180));
  // J232 feeds every blade: one station per spindle by default.
  REQUIRE(s.feed.stations.size() == 3);
  CHECK(s.feed.stations[2].spindle == 2);
  CHECK(s.feed.stations[2].radius == Approx(12.5 * units::inch - 0.0508));
  CHECK(s.reach() == Approx(std::hypot(0.05, 0.597) + 12.5 * units::inch));
  CHECK(s.tip_speed() == Approx(2700 * units::rpm * 12.5 * units::inch));
}

TEST_CASE("deck: bad decks are refused with the key and what was expected", "[deck][input]") {
  using Catch::Contains;
  CHECK_THROWS_WITH(read(kThree + "[blade]\nspeed = \"1000 rpm\"\n"), Contains("give either [blade]") && Contains("not both"));
  CHECK_THROWS_WITH(read(kBlades + "[[spindles]]\nblade = \"nope\"\n"), Contains("spindles[1].blade") && Contains("[blades.nope]"));
  CHECK_THROWS_WITH(read(kBlades + "[blades.spare]\nspeed = \"1 rpm\"\n[[spindles]]\nblade = \"bar\"\n"),
                    Contains("blades.spare") && Contains("no spindle uses this blade"));
  CHECK_THROWS_WITH(read(kBlades + "[[spindles]]\nblade = \"bar\"\n[[spindles]]\nblade = \"bar\"\nx = \"0.5 m\"\n"),
                    Contains("spindles[2].x") && Contains("overlaps spindle 1"));
  CHECK_THROWS_WITH(read(kThree + "[[feed.stations]]\nspindle = 4\nradius = \"10 in\"\n"),
                    Contains("feed.stations[1].spindle") && Contains("from 1 to 3"));
  CHECK_THROWS_WITH(read(kThree + "[[feed.stations]]\nspindle = 2\nradius = \"13 in\"\n"), Contains("feed.stations[1].radius"));
  CHECK_THROWS_WITH(read(kThree + "[housing]\ndeck_radius = \"1 m\"\n"), Contains("housing.deck_radius") && Contains("margin"));
  CHECK_THROWS_WITH(read(kThree + "[[spindles]]\nblade = \"bar\"\nsense = \"up\"\n"), Contains("\"ccw\", \"cw\""));
}

TEST_CASE("deck: a clockwise blade strikes the mirror image of a counter-clockwise one", "[deck][feed]") {
  const auto s = read(kThree);
  const auto edges = feed::leading_edges(s.spindles[0].blade);
  feed::NailDrop d;
  d.length = 0.0508, d.mass = 0.002;
  d.fall_speed = 2.4;
  for (const double phase : {0.3, 1.7, 4.0}) {
    d.position = {0.2, 0.15};
    d.blade_phase = phase;
    const auto ccw = feed::find_strike(d, edges, s.spindles[0].blade.omega, s.spindles[0].geometry, +1);
    d.position = {0.2, -0.15};
    d.blade_phase = -phase;
    const auto cw = feed::find_strike(d, edges, s.spindles[0].blade.omega, s.spindles[0].geometry, -1);
    REQUIRE(ccw.has_value() == cw.has_value());
    if (!ccw) continue;
    CHECK(cw->time == Approx(ccw->time).margin(1e-12));
    CHECK(cw->azimuth == Approx(-ccw->azimuth).margin(1e-12));
    CHECK(cw->radius == Approx(ccw->radius).margin(1e-12));
  }
}

TEST_CASE("deck: the three-spindle deck runs, its outline encloses every tip circle, nails meet other blades", "[deck][assess]") {
  auto s = scenario::read_scenario(scenario_path("deck-72in-three-spindle.toml"));
  s.run.replicates = 100;
  // The generated skirt lies outside every tip circle, and the opening cuts it.
  const auto soup = scene::build_scene_soup(s);
  std::size_t skirt_points = 0;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (soup.labels[t] == scene::Surface::Housing)
      for (auto v : soup.triangles[t]) {
        const auto& p = soup.points[v];
        if (p.z() > s.housing.skirt_bottom + s.housing.skirt_depth - 1e-9) continue;  // the plate: only the skirt's foot
        for (const auto& sp : s.spindles) CHECK(std::hypot(p.x() - sp.x, p.y() - sp.y) >= sp.blade.tip_radius() + 0.0499);
        ++skirt_points;
      }
  CHECK(skirt_points > 100);
  const assess::Simulator sim(s);
  const auto a = assess::run_assessment(sim, 2);
  const auto sum = assess::summarise(a, s);
  CHECK(sum.validity.valid);
  CHECK(a.struck > a.nails / 2);
  CHECK(a.strikes.mean() > 1.2);  // thrown into the neighbouring blades' discs
  // ...and the same on one thread, bit for bit.
  const auto one = assess::run_assessment(sim, 1);
  CHECK(one.strikes.counts == a.strikes.counts);
  CHECK(one.shares[assess::PuncturesOutside].counts == a.shares[assess::PuncturesOutside].counts);
}
