// Fitting the restitution law to measured impacts (j232 calibrate), drop tests, and the CSV
// reader they share.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "blade/blade_model.hpp"
#include "scenario/csv_reader.hpp"
#include "scenario/impact_input.hpp"
#include "scenario/input_error.hpp"
#include "scenario/toml_override.hpp"
#include "scenario/toml_reader.hpp"
#include "study/calibration.hpp"

using namespace j232;

namespace {
const std::string kSource = J232_SOURCE_DIR;

// The lab straight blade at `rpm`, struck by an object of `grams`, "measured" with `law`.
study::CalibrationCase synthetic(double rpm, double grams, const blade::Restitution& law) {
  toml::table doc = scenario::parse_toml_file(kSource + "/scenarios/impact/lab-straight.toml");
  scenario::set_key(doc, "blade.speed", std::to_string(rpm) + " rpm", "test");
  scenario::set_key(doc, "object.mass", std::to_string(grams) + " g", "test");
  study::CalibrationCase c;
  c.name = std::to_string(rpm) + " rpm, " + std::to_string(grams) + " g";
  c.input = scenario::read_impact_case(doc, "lab-straight.toml");
  const blade::BladeModel model(c.input.blade);
  c.measured_speed = blade::solve_impact(model, c.input.location, c.input.object, law).contact.velocity_after.norm();
  return c;
}
}  // namespace

TEST_CASE("calibrate: a constant e is recovered from speeds it made, and predicts held-out cases", "[calibrate]") {
  std::vector<study::CalibrationCase> cases;
  for (double grams : {10.0, 20.0, 40.0, 80.0}) cases.push_back(synthetic(413, grams, blade::Restitution::constant(0.7)));
  const auto r = study::calibrate(cases, study::LawKind::Constant, "synthetic");
  REQUIRE(r.parameters.size() == 1);
  CHECK(r.fitted.e == Approx(0.7).epsilon(1e-6));
  CHECK(r.parameters[0].low <= 0.7);
  CHECK(r.parameters[0].high >= 0.7);
  CHECK(r.rms_fitted < 1e-6);
  CHECK(r.rms_held_out < 1e-6);
  CHECK(r.rms_as_given > 0.05);  // the files' own e = 0.9 throws faster
  // Noise widens the interval but it still covers the truth.
  cases[0].measured_speed *= 1.03, cases[1].measured_speed *= 0.98, cases[2].measured_speed *= 1.01, cases[3].measured_speed *= 0.985;
  const auto noisy = study::calibrate(cases, study::LawKind::Constant, "synthetic");
  CHECK(noisy.parameters[0].low < 0.7);
  CHECK(noisy.parameters[0].high > 0.7);
  CHECK(noisy.rms_held_out > noisy.rms_fitted);
}

TEST_CASE("calibrate: a power law is recovered from cases at several speeds", "[calibrate]") {
  const auto law = blade::Restitution::power_law(1.06, -0.25, 1.0);
  std::vector<study::CalibrationCase> cases;
  for (double rpm : {200.0, 400.0, 800.0, 1600.0, 3200.0}) cases.push_back(synthetic(rpm, 19, law));
  const auto r = study::calibrate(cases, study::LawKind::PowerLaw, "synthetic");
  REQUIRE(r.parameters.size() == 2);
  // The fitted coefficient is e at the cases' typical approach speed.
  CHECK(r.fitted.at(10.0) == Approx(law.at(10.0)).epsilon(1e-5));
  CHECK(r.fitted.exponent == Approx(-0.25).epsilon(1e-4));
  CHECK(r.rms_fitted < 1e-6);
  // At one speed only, the exponent cannot be found: refused, with what to do.
  std::vector<study::CalibrationCase> one_speed;
  for (double grams : {10.0, 20.0, 40.0, 80.0}) one_speed.push_back(synthetic(413, grams, law));
  CHECK_THROWS_WITH(study::calibrate(one_speed, study::LawKind::PowerLaw, "same.csv"), Catch::Contains("too narrow to fit how e changes"));
  CHECK_THROWS_WITH(study::calibrate({cases[0], cases[1]}, study::LawKind::Constant, "few.csv"), Catch::Contains("needs at least 3"));
}

TEST_CASE("calibrate: report 445-1 Table 3.1", "[calibrate][report]") {
  const auto cases = study::read_calibration_cases(kSource + "/scenarios/calibration/report-445-1-table-3-1.csv");
  REQUIRE(cases.size() == 8);
  const auto r = study::calibrate(cases, study::LawKind::Constant, "table-3-1");
  // As given (the report's e = 0.90-0.92), j232 overpredicts every measured speed by 15-34 %
  // (docs/validation.md §1); a fitted e of about 0.59 brings the errors to a few per cent.
  for (const auto& k : r.cases) {
    CHECK(k.as_given / k.measured - 1 > 0.15);
    CHECK(k.as_given / k.measured - 1 < 0.34);
  }
  CHECK(r.cases[0].as_given / 0.00508 == Approx(3037).margin(1));
  CHECK(r.fitted.e == Approx(0.59).margin(0.01));
  CHECK(r.parameters[0].low > 0.5);
  CHECK(r.parameters[0].high < 0.7);
  CHECK(r.rms_as_given == Approx(0.223).margin(0.002));
  CHECK(r.rms_fitted < 0.05);
  CHECK(r.rms_held_out < 0.06);
  CHECK(r.rms_held_out > r.rms_fitted);
}

TEST_CASE("drop tests: e = sqrt(rebound / drop height) with an interval", "[calibrate]") {
  const std::vector<study::DropTest> drops = {{1.0, 0.81, 2}, {1.0, 0.8281, 3}, {0.5, 0.3969405, 4}};
  const auto r = study::restitution_from_drops(drops);
  CHECK(r.e[0] == Approx(0.9));
  CHECK(r.e[1] == Approx(0.91));
  CHECK(r.e[2] == Approx(0.891));
  CHECK(r.mean == Approx((0.9 + 0.91 + 0.891) / 3));
  CHECK(r.low < r.mean);
  CHECK(r.high > r.mean);
  CHECK(r.impact_speed[0] == Approx(std::sqrt(2 * 9.80665)));
}

TEST_CASE("csv: quoted fields, comments, and errors that name the line", "[calibrate][csv]") {
  const auto t = scenario::parse_csv("# a comment\n\ncase, value\n\"a, b\",\" 2 \"\n\"say \"\"hi\"\"\",3\n", "t.csv");
  CHECK(t.header == std::vector<std::string>{"case", "value"});
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0].fields == std::vector<std::string>{"a, b", " 2 "});
  CHECK(t.rows[1].fields[0] == "say \"hi\"");
  CHECK(t.rows[1].line == 5);
  CHECK(t.column("value") == 1);
  CHECK(t.column("nope") == -1);
  CHECK_THROWS_WITH(scenario::parse_csv("a,b\n1,2,3\n", "t.csv"), Catch::Contains("t.csv:2: 3 fields; expected 2"));
  CHECK_THROWS_WITH(scenario::parse_csv("a,b\n\"1,2\n", "t.csv"), Catch::Contains("t.csv:2: a quoted field is not closed"));
  CHECK_THROWS_WITH(scenario::parse_csv("# only a comment\n", "t.csv"), Catch::Contains("expected a header line and at least one row"));
}
