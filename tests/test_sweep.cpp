// Parameter studies: the sweep files for report 445-1 Figs 2.8-2.16 reproduce the
// report's first program point by point, show the trends the report describes where the
// mechanics agree with it, and Monte Carlo sweeps give P(pass) with intervals.
#include <catch2/catch.hpp>
#include <cmath>
#include <fmt/format.h>
#include <set>
#include <string>
#include <vector>

#include "field/hazard_run.hpp"
#include "report_fortran.hpp"
#include "scenario/scenario_reader.hpp"
#include "scenario/input_error.hpp"
#include "report/sweep_report.hpp"
#include "study/sweep.hpp"
#include "units/quantity.hpp"

using namespace j232;

namespace {

std::string sweep_file(int figure) { return fmt::format("{}/sweeps/report-445-1/fig-2-{:02d}.toml", J232_SOURCE_DIR, figure); }

// Report 445-1, Appendix A, first program (report_fortran.hpp), blade length 2 ft, exact pi.
double fortran_va2(double rpm, double blade_lb, double e, double objvel_ft_min, double r_ft, double w1_lb) {
  return test::fortran_straight_va2(rpm, 2.0, blade_lb, e, objvel_ft_min, r_ft, w1_lb, units::pi);
}

struct Sweep {
  study::SweepSpec spec;
  study::SweepTable table;
  double at(const study::SweepTable::Row& r, const char* col) const { return r.values[study::column(table, col)]; }
};

Sweep run(int figure) {
  Sweep s{study::read_sweep_file(sweep_file(figure)), {}};
  s.table = study::run_sweep(s.spec, 1, nullptr);
  return s;
}

}  // namespace

TEST_CASE("sweep: Figs 2.8-2.15 equal the report's first program at every point", "[sweep][validation]") {
  for (int figure = 8; figure <= 15; ++figure) {
    INFO("Fig 2." << figure);
    const Sweep s = run(figure);
    std::size_t curves = 1;
    for (const auto& a : s.spec.series) curves *= a.values.size();
    REQUIRE(s.table.rows.size() == curves * 8);
    for (const auto& r : s.table.rows) {
      const double w1 = s.at(r, "object_mass_kg") / units::pound, w2 = s.at(r, "blade_mass_kg") / units::pound;
      const double expected =
          fortran_va2(s.at(r, "blade_speed_rpm"), w2, s.at(r, "restitution"), 440.0, s.at(r, "contact_radius_m") / units::foot, w1);
      CHECK(s.at(r, "object_speed_after_ft_min") == Approx(expected).epsilon(1e-9));
      // The report's dimensionless velocity Z = (VA2 - 440) / (4 pi rpm).
      CHECK(s.at(r, "dimensionless_velocity") == Approx((expected - 440.0) / (4 * units::pi * s.at(r, "blade_speed_rpm"))).epsilon(1e-9));
    }
    // Object masses as the Fortran's W1(N) = 3.1071429 (N - 1) + 0.25 lb.
    for (std::size_t n = 0; n < 8; ++n)
      CHECK(s.at(s.table.rows[n], "object_mass_kg") / units::pound == Approx(3.1071429 * static_cast<double>(n) + 0.25).epsilon(1e-7));
  }
}

TEST_CASE("sweep: the trends report 445-1 describes for Figs 2.8-2.15", "[sweep][validation]") {
  SECTION("Fig 2.8: a harder object (higher e) is thrown faster") {
    const Sweep s = run(8);
    for (std::size_t n = 0; n < 8; ++n)
      for (std::size_t c = 1; c < 4; ++c)
        CHECK(s.at(s.table.rows[c * 8 + n], "object_speed_after_m_s") > s.at(s.table.rows[(c - 1) * 8 + n], "object_speed_after_m_s"));
  }
  SECTION("Fig 2.12: object speed nearly proportional to blade speed") {
    const Sweep s = run(12);
    for (std::size_t n = 0; n < 8; ++n) {
      const double v700 = s.at(s.table.rows[n], "object_speed_after_m_s"), v1000 = s.at(s.table.rows[24 + n], "object_speed_after_m_s");
      CHECK(v1000 / v700 == Approx(1000.0 / 700.0).epsilon(0.03));
    }
  }
  SECTION("Figs 2.14, 2.15: blade mass matters only for heavy objects") {
    for (int figure : {14, 15}) {
      const Sweep s = run(figure);
      auto spread = [&](std::size_t n) {
        return s.at(s.table.rows[24 + n], "object_speed_after_m_s") / s.at(s.table.rows[n], "object_speed_after_m_s") - 1;
      };
      CHECK(spread(0) < 0.02);  // 0.25 lb: 22 lb vs 16 lb blade within 2 %
      CHECK(spread(7) > 0.15);  // 22 lb object: more than 15 % apart
    }
  }
  SECTION("Figs 2.9, 2.10: in the true dimensionless form the blade-mass curves collapse") {
    // v'/(omega L) depends on the mass ratio (and e, R/L, v0/(omega L)) only. The report's
    // curves separate because the Fortran plots every curve against W1 / IW2(4), the
    // heaviest blade's mass (ZZ is overwritten inside the loop).
    const Sweep s = run(9);
    for (std::size_t n = 0; n < 8; ++n) {
      // 16 lb, 1000 rpm (curve 3) and 22 lb, 1000 rpm (curve 7) at equal object mass:
      const auto& light = s.table.rows[3 * 8 + n];
      const auto& heavy = s.table.rows[7 * 8 + n];
      CHECK(s.at(heavy, "object_speed_after_m_s") >= s.at(light, "object_speed_after_m_s"));  // the report's observation
    }
    // ... and at equal mass ratio they agree exactly: a 16 lb blade throwing objects 16/22
    // as heavy as a 22 lb blade's.
    study::SweepSpec scaled = s.spec;
    scaled.series.clear();
    scaled.fixed = {study::make_setting(study::parameter_info("blade_mass"), "16 lb", "", std::nullopt, "test")};
    for (auto& x : scaled.x.values) x.si *= 16.0 / 22.0;
    const auto t = study::run_sweep(scaled, 1, nullptr);
    const std::size_t z = study::column(t, "dimensionless_velocity");
    for (std::size_t n = 0; n < 8; ++n)
      CHECK(t.rows[n].values[z] == Approx(s.at(s.table.rows[7 * 8 + n], "dimensionless_velocity")).epsilon(1e-9));
  }
}

TEST_CASE("sweep: Fig 2.16 pivot position keeps the blade's mass and tip radius", "[sweep][validation]") {
  const Sweep s = run(16);
  REQUIRE(s.table.rows.size() == 4 * 18);
  for (const auto& r : s.table.rows) CHECK(s.at(r, "blade_mass_kg") == Approx(20 * units::pound));
  // A 2 g nail is too light for the blade to feel: the pivot makes no difference.
  double lo = 1e9, hi = 0;
  for (std::size_t i = 0; i < 18; ++i)
    lo = std::min(lo, s.at(s.table.rows[i], "dimensionless_velocity")), hi = std::max(hi, s.at(s.table.rows[i], "dimensionless_velocity"));
  CHECK(hi / lo - 1 < 0.002);
  // A heavy object is thrown slower by a blade pinned farther out than by one pinned near
  // the spindle (the report's conclusion), with the slowest near S/L = 1/4.
  const std::size_t heavy = 3 * 18;
  const auto v = [&](std::size_t i) { return s.at(s.table.rows[heavy + i], "dimensionless_velocity"); };
  CHECK(v(17) > v(8));  // S/L 0.95 vs 0.5
  CHECK(v(8) > v(3));   // S/L 0.5 vs 0.25
}

TEST_CASE("sweep: pivot_position refuses a blade it cannot re-split", "[sweep]") {
  blade::Blade b;
  b.omega = 100;
  b.hub.bar_mass = 10;
  b.hub.bar_length = 1;
  CHECK_THROWS_AS(study::set_pivot_position(b, 0.5), std::invalid_argument);
  b.hub.bar_mount = blade::BarMount::Centre;
  b.arms.push_back({0.0, 0.5, {blade::Link{0.5, 2.0, std::nullopt, std::nullopt, false}}});
  b.arms.push_back({units::pi, 0.5, {blade::Link{0.5, 2.0, std::nullopt, std::nullopt, false}}});
  const double mass = b.mass(), tip = b.tip_radius();
  study::set_pivot_position(b, 0.25);
  CHECK(b.mass() == Approx(mass));
  CHECK(b.tip_radius() == Approx(tip));
  CHECK(b.arms[0].pivot_radius == Approx(0.75 * tip));
  CHECK(b.hub.bar_length == Approx(1.5 * tip));
}

TEST_CASE("sweep: over a J232 scenario, P(pass) with its interval at every point", "[sweep][assess][long]") {
  study::SweepSpec spec;
  spec.source = "test";
  spec.base = std::string(J232_SOURCE_DIR) + "/scenarios/highway-pivoted-raised-skirt.toml";
  spec.x = study::parse_axis("housing.skirt_bottom=6 in,1 in", "--x");  // a key of the file itself
  spec.replicates = 40;
  const auto t = study::run_sweep(spec, 2, nullptr);
  REQUIRE(t.kind == study::SweepTable::Kind::Assessment);
  REQUIRE(t.rows.size() == 2);
  for (const auto& r : t.rows) {
    const double p = r.values[study::column(t, "p_pass")];
    CHECK(r.values[study::column(t, "p_pass_low")] <= p);
    CHECK(p <= r.values[study::column(t, "p_pass_high")]);
    for (const char* c : {"hits_zone", "punctures_zone", "hits_outside", "punctures_outside"}) {  // single tests' spread
      const std::string name = c;
      CHECK(r.values[study::column(t, "q05_" + name)] <= r.values[study::column(t, "q95_" + name)]);
      CHECK(r.values[study::column(t, "share_" + name)] >= 0);
    }
    CHECK(r.values[study::column(t, "limit_punctures_outside")] == 0.05);
  }
  // Raised skirt fails; lowered below the blade (1 in) it contains most nails and passes far
  // more often.
  CHECK(t.rows[0].values[study::column(t, "p_pass")] < 0.1);
  CHECK(t.rows[1].values[study::column(t, "p_pass")] > t.rows[0].values[study::column(t, "p_pass")] + 0.4);
  CHECK(t.rows[0].x == Approx(6 * units::inch));
  const auto charts = report::sweep_charts(spec, t);
  REQUIRE(charts.size() == 5);  // P(pass), then each criterion's share with its band and limit
  CHECK(charts[0].first == "pass-probability");
  CHECK(charts[4].first == "share-punctures_outside");
  CHECK(charts[4].second.find("limit 5 %") != std::string::npos);
}

TEST_CASE("sweep: bad sweep input names the key and value", "[sweep][input]") {
  CHECK_THROWS_WITH(study::parse_axis("restitution=0.5,1.5", "--x"), Catch::Contains("1.5") && Catch::Contains("between 0 and 1"));
  CHECK_THROWS_WITH(study::parse_axis("blade_speed=700 rmp", "--x"), Catch::Contains("rmp"));
  CHECK_THROWS_WITH(study::parse_axis("blade_speed", "--series"), Catch::Contains("PARAMETER=V1,V2"));
}

TEST_CASE("sweep: an opening or a curtain left without a top takes the deck plate's, and keeps it through a named parameter", "[sweep]") {
  scenario::Scenario s;
  scenario::OpeningSpec open;
  open.azimuth = {-0.3, 0.3};
  open.chute_length = 0.2;
  scenario::GuardSpec curtain;
  curtain.along = {{0.5, -0.2}, {0.5, 0.2}};
  s.housing.openings = {open};
  s.housing.guards = {curtain};
  const double plate = s.housing.skirt_bottom + s.housing.skirt_depth;
  CHECK(s.housing.opening_top(s.housing.openings[0]) == plate);
  CHECK(s.housing.chute_end_top(s.housing.openings[0]) == plate);
  CHECK(s.housing.guard_top(s.housing.guards[0]) == plate);
  // Written ones are kept as written.
  s.housing.openings[0].top = 0.1;
  CHECK(s.housing.chute_end_top(s.housing.openings[0]) == 0.1);
  s.housing.openings[0].top.reset();
  // A named parameter writes them in where the deck put them: a deeper skirt afterwards
  // leaves them there, and a cut height moves them with the deck.
  auto set = s;
  study::apply(study::make_setting(study::parameter_info("restitution"), "0.5", "", std::nullopt, "test"), set);
  set.housing.skirt_depth += 0.05;
  CHECK(set.housing.opening_top(set.housing.openings[0]) == plate);
  CHECK(set.housing.guard_top(set.housing.guards[0]) == plate);
  // A cut height set directly moves a left-out top with the deck, once.
  auto shoulder = scenario::read_scenario(std::string(J232_SOURCE_DIR) + "/scenarios/field/batwing-highway-shoulder.toml");
  for (auto& o : shoulder.housing.openings) o.top.reset(), o.chute_end_top.reset();
  const auto before = shoulder;
  study::set_cut_height(shoulder, 4 * units::inch);  // the file's blades at 3 in: 1 in up
  for (std::size_t i = 0; i < shoulder.housing.openings.size(); ++i)
    CHECK(shoulder.housing.opening_top(shoulder.housing.openings[i]) ==
          Approx(before.housing.opening_top(before.housing.openings[i]) + units::inch).epsilon(1e-12));
}

TEST_CASE("sweep: cut_height sets the whole mower, not the ground, and refuses what would go under the turf", "[sweep][field]") {
  const std::string shoulder = std::string(J232_SOURCE_DIR) + "/scenarios/field/batwing-highway-shoulder.toml";
  auto s = scenario::read_scenario(shoulder);
  const auto before = s;
  study::set_cut_height(s, 4 * units::inch);  // the file's blades at 3 in: everything 1 in up
  for (std::size_t k = 0; k < s.spindles.size(); ++k)
    CHECK(s.spindles[k].geometry.height == Approx(before.spindles[k].geometry.height + units::inch));
  CHECK(s.housing.skirt_bottom == Approx(before.housing.skirt_bottom + units::inch));
  for (std::size_t i = 0; i < s.housing.openings.size(); ++i)
    CHECK(s.housing.opening_top(s.housing.openings[i]) == Approx(before.housing.opening_top(before.housing.openings[i]) + units::inch));
  for (std::size_t i = 0; i < s.housing.guards.size(); ++i)
    CHECK(s.housing.guards[i].bottom == Approx(before.housing.guards[i].bottom + units::inch));
  CHECK(s.front_gap().value() == Approx(before.front_gap().value() + units::inch));
  // The skirt's foot (1.5 in below the blades) under the turf at a 1.4-in cut; a mesh deck.
  auto low = before;
  CHECK_THROWS_WITH(study::set_cut_height(low, 1.4 * units::inch), Catch::Contains("skirt's foot") && Catch::Contains("below the turf"));
  // A J232 scenario's board is set from the blades' plane as it is read: not moved after.
  auto j232 = scenario::read_scenario(std::string(J232_SOURCE_DIR) + "/scenarios/highway-pivoted.toml");
  CHECK_THROWS_WITH(study::set_cut_height(j232, 4 * units::inch), Catch::Contains("J232 scenario's board"));
}

TEST_CASE("sweep: over a field scenario, each point a hazard run, the same as that run made directly", "[sweep][field]") {
  study::SweepSpec spec;
  spec.source = "test";
  spec.base = std::string(J232_SOURCE_DIR) + "/scenarios/field/batwing-highway-shoulder.toml";
  spec.x = study::parse_axis("cut_height=2.5 in,4 in", "--x");
  spec.objects = 2000;
  const auto t = study::run_sweep(spec, 2, nullptr);
  REQUIRE(t.kind == study::SweepTable::Kind::Hazard);
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0].x == Approx(2.5));  // on the axis in inches
  CHECK(t.planes == std::vector<std::string>{"traffic lane", "path on the left"});
  const std::size_t path = study::column(t, "plane_path_on_the_left_hazardous_per_km");
  CHECK(study::column(t, "plane_traffic_lane_hazardous_per_km_high") < path);
  for (const auto& r : t.rows) {
    CHECK(r.values[path + 1] <= r.values[path]);
    CHECK(r.values[path] <= r.values[path + 2]);
    CHECK(r.values[study::column(t, "objects")] == 2000);
  }
  CHECK(t.rows[1].values[path] < t.rows[0].values[path]);  // a higher cut: fewer hazardous crossings
  // The 4-in point, made directly.
  auto s = scenario::read_scenario(spec.base);
  study::set_cut_height(s, 4 * units::inch);
  s.field.objects_simulated = 2000;
  const field::FieldSimulator sim(s);
  const auto sum = field::summarise(sim, field::run_hazard(sim, 1));
  CHECK(t.rows[1].values[study::column(t, "thrown_per_km")] == sum.thrown_per_km);
  CHECK(t.rows[1].values[path] == sum.planes[1].hazardous_per_km.value);
  CHECK(t.rows[1].values[study::column(t, "left_hazard_distance_upper_m")] == sum.directions[0].hazard_distance_upper);
  const auto charts = report::sweep_charts(spec, t);
  REQUIRE(charts.size() == 7);  // each plane, the hazard distance each way, the objects thrown
  CHECK(charts[1].first == "plane-2");
  CHECK(charts[1].second.find("path on the left") != std::string::npos);
  CHECK(charts[2].first == "hazard-distance-left");
  CHECK(charts[6].first == "thrown");
  // Objects are a field's; replicates a J232 scenario's.
  spec.replicates = 10;
  CHECK_THROWS_WITH(study::run_sweep(spec, 1, nullptr), Catch::Contains("run.objects"));
  study::SweepSpec j232 = spec;
  j232.base = std::string(J232_SOURCE_DIR) + "/scenarios/highway-pivoted.toml";
  j232.replicates = 0;
  CHECK_THROWS_WITH(study::run_sweep(j232, 1, nullptr), Catch::Contains("field scenario"));
}

TEST_CASE("sweep: a point that cannot be assessed is recorded with why, and the sweep goes on", "[sweep][field]") {
  study::SweepSpec spec;
  spec.source = "test";
  spec.name = "cut";
  spec.base = std::string(J232_SOURCE_DIR) + "/scenarios/field/batwing-highway-shoulder.toml";
  spec.x = study::parse_axis("cut_height=1.2 in,4 in", "--x");  // at 1.2 in the skirt's foot would be under the turf
  spec.objects = 1000;
  const auto t = study::run_sweep(spec, 2, nullptr);
  REQUIRE(t.rows.size() == 2);
  CHECK(t.any_invalid());
  CHECK_THAT(t.rows[0].invalid, Catch::Contains("cut_height = 1.2 in") && Catch::Contains("skirt's foot"));
  CHECK(t.rows[0].values.empty());
  CHECK(t.rows[1].invalid.empty());
  CHECK(t.rows[1].values.size() == t.columns.size());
  // The CSV: the point's row with empty values and the reason in a last `note` column.
  const std::string csv = report::sweep_csv(spec, t);
  const auto first_line_end = csv.find('\n');
  CHECK(csv.substr(0, first_line_end).size() > 5);
  CHECK(csv.compare(first_line_end - 5, 5, ",note") == 0);
  const auto row = csv.substr(first_line_end + 1, csv.find('\n', first_line_end + 1) - first_line_end - 1);
  CHECK_THAT(row, Catch::StartsWith("\"\",\"1.2 in\",1.2" + std::string(t.columns.size(), ',') + ",\"") && Catch::Contains("skirt's foot"));
  // The charts draw the one point assessed and name the other in their captions.
  for (const auto& [name, svg] : report::sweep_charts(spec, t)) {
    INFO(name);
    CHECK_THAT(svg, Catch::Contains("Not assessed, so not drawn") && Catch::Contains("cut_height = 1.2 in"));
    CHECK(svg.find("nan") == std::string::npos);
  }
  // A gap is not bridged: with a point not assessed between two that are, each series' line
  // is drawn in two pieces (one more unfilled path than without the middle point).
  spec.objects = 500;
  spec.x = study::parse_axis("cut_height=4 in,4.5 in", "--x");
  const auto whole = report::sweep_charts(spec, study::run_sweep(spec, 2, nullptr));
  spec.x = study::parse_axis("cut_height=4 in,1.2 in,4.5 in", "--x");
  const auto gapped = report::sweep_charts(spec, study::run_sweep(spec, 2, nullptr));
  const auto lines = [](const std::string& svg) {
    std::size_t n = 0;
    for (auto at = svg.find("fill=\"none\""); at != std::string::npos; at = svg.find("fill=\"none\"", at + 1)) ++n;
    return n;
  };
  REQUIRE(whole.back().first == "thrown");
  CHECK(lines(gapped.back().second) == lines(whole.back().second) + 1);
  // No point assessed at all: refused, with the first point's reason.
  spec.x = study::parse_axis("cut_height=1.1 in,1.2 in", "--x");
  CHECK_THROWS_WITH(study::run_sweep(spec, 2, nullptr), Catch::Contains("no point could be assessed") && Catch::Contains("skirt's foot"));
}
