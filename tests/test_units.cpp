#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include <fmt/format.h>

#include "scenario/scenario.hpp"
#include "units/quantity.hpp"
#include "units/sin_cos.hpp"

using namespace j232::units;

TEST_CASE("units: common mower quantities convert to SI", "[units]") {
  CHECK(parse("22 lb", Kind::Mass) == Approx(9.97903214));
  CHECK(parse("170 g", Kind::Mass) == Approx(0.170));
  CHECK(parse("24 in", Kind::Length) == Approx(0.6096));
  CHECK(parse("2 ft", Kind::Length) == Approx(0.6096));
  CHECK(parse("1000 rpm", Kind::AngularSpeed) == Approx(104.71975512));
  CHECK(parse("104.71975512 rad/s", Kind::AngularSpeed) == Approx(104.71975512));
  CHECK(parse("1000 rev/min", Kind::AngularSpeed) == Approx(104.71975512));
  CHECK(parse("440 ft/min", Kind::Speed) == Approx(2.2352));
  CHECK(parse("5 mph", Kind::Speed) == Approx(2.2352));
  CHECK(parse("18 km/h", Kind::Speed) == Approx(5.0));
  CHECK(parse("1.2 lb ft^2", Kind::Inertia) == Approx(1.2 * pound * foot * foot));
  CHECK(parse("0.05 kg*m^2", Kind::Inertia) == Approx(0.05));
  CHECK(parse("110 J/m", Kind::EnergyPerLength) == Approx(110.0));
  CHECK(parse("9.81 m/s^2", Kind::Acceleration) == Approx(9.81));
  CHECK(parse("1.2 kg/m^3", Kind::Density) == Approx(1.2));
  CHECK(parse("90 deg", Kind::Angle) == Approx(pi / 2));
  CHECK(parse("0.9", Kind::Dimensionless) == Approx(0.9));
  CHECK(parse("90 %", Kind::Dimensionless) == Approx(0.9));
  CHECK(parse("  -3.5e-1 m ", Kind::Length) == Approx(-0.35));
  CHECK(parse("+2 in", Kind::Length) == Approx(0.0508));
}

TEST_CASE("units: wrong or unknown units are refused with a useful message", "[units]") {
  CHECK_THROWS_WITH(parse("22 lbs", Kind::Mass), Catch::Contains("unknown unit \"lbs\""));
  CHECK_THROWS_WITH(parse("22 lb", Kind::Length), Catch::Contains("expected a length"));
  CHECK_THROWS_WITH(parse("22", Kind::Mass), Catch::Contains("has no unit"));
  CHECK_THROWS_WITH(parse("lb", Kind::Mass), Catch::Contains("does not start with a number"));
  CHECK_THROWS_WITH(parse("", Kind::Mass), Catch::Contains("does not start with a number"));
  CHECK_THROWS_WITH(parse("30 deg", Kind::Dimensionless), Catch::Contains("wrong kind of unit"));
  CHECK_THROWS_WITH(parse("3 m/", Kind::Speed), Catch::Contains("ends with an operator"));
  CHECK_THROWS_WITH(parse("3 m^x", Kind::Length), Catch::Contains("bad exponent"));
  CHECK_THROWS_WITH(parse("3 m//s", Kind::Speed), Catch::Contains("misplaced"));
  CHECK_THROWS_WITH(parse("1000 rpm", Kind::Speed), Catch::Contains("expected a speed"));
  CHECK_THROWS(parse("nan m", Kind::Length));
  CHECK_THROWS(parse("inf m", Kind::Length));
}

TEST_CASE("units: exponents are bounded, so no unit overflows (audit finding 6)", "[units][robust]") {
  CHECK_THROWS_WITH(parse("1 J^2147483647", Kind::Energy), Catch::Contains("bad exponent"));
  CHECK_THROWS_WITH(parse("1 m/s^-2147483648", Kind::Speed), Catch::Contains("bad exponent"));
  CHECK_THROWS_WITH(parse("1 m^2147483647 m^2147483647 m^3", Kind::Length), Catch::Contains("bad exponent"));
  CHECK_THROWS_WITH(parse("1 m^12 m^12 m^12 m^12 m^12", Kind::Length), Catch::Contains("out of any physical range"));
  CHECK_THROWS(parse("1e300 mi^12", Kind::Length));
  CHECK_THROWS(parse("1e300 mi^3 / mm^2", Kind::Length));  // overflows to infinity in SI
  CHECK(parse("2 m^12 / m^11", Kind::Length) == Approx(2.0));
}

#include "report/text_safety.hpp"

TEST_CASE("text safety: terminal, CSV, links and folder names (audit finding 8)", "[robust]") {
  using namespace j232::report;
  CHECK(terminal_safe("a\x1b[31mb\x07") == "a?[31mb?");
  CHECK(csv_text_cell("=HYPERLINK(\"x\")") == "\"'=HYPERLINK(\"\"x\"\")\"");
  CHECK(csv_text_cell("-2+3") == "'-2+3");
  CHECK(csv_text_cell("plain") == "plain");
  CHECK(relative_url("javascript:alert(3)/report.html") == "./javascript%3Aalert%283%29/report.html");
  CHECK(safe_folder_name("..") == "__");
  CHECK(safe_folder_name("") == "scenario");
  CHECK(safe_folder_name("a b/c") == "a_b_c");
}

TEST_CASE("sin_cos agrees with the library's sin and cos to 2e-16 over the angles a search meets", "[units]") {
  std::mt19937_64 rng(7);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    // Angles from tiny to 1e6 rad, both signs, and the quadrant boundaries' neighbours.
    const double magnitude = std::pow(10.0, std::uniform_real_distribution<double>(-8, 6)(rng));
    double x = (i % 2 ? -1 : 1) * magnitude;
    if (i % 7 == 0) x = std::nearbyint(x / (0.5 * pi)) * 0.5 * pi + 1e-12 * (i % 3 - 1);
    const SinCos sc = sin_cos(x);
    worst = std::max({worst, std::abs(sc.sin - std::sin(x)), std::abs(sc.cos - std::cos(x))});
  }
  CHECK(worst < 2e-16 * 8);  // a few ulp of 1 at 1e6 rad, where the library's own reduction differs
  CHECK(sin_cos(0.0).sin == 0.0);
  CHECK(sin_cos(0.0).cos == 1.0);
}

TEST_CASE("defaults given in degrees print back as the degrees they are", "[units]") {
  // A default held as a rounded radian (0.0873 for 5 deg) printed back as 5.00192 deg.
  const auto deg = [](double rad) { return fmt::format("{:g}", rad / degree); };
  CHECK(deg(j232::scenario::FeedSpec{}.tilt_max) == "5");
  CHECK(deg(j232::scenario::EdgeSpec{}.bevel_angle) == "30");
  CHECK(deg(j232::scenario::EdgeSpec{}.sail_angle) == "45");
  CHECK(deg(j232::scenario::GroundSpec{}.roughness) == "10");
  CHECK(deg(parse("5 deg", Kind::Angle)) == "5");
}
