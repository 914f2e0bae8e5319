#pragma once
// The units a field report is shown in (`--units si|us` on `j232 hazard` and `j232 compare`):
// SI, or the US customary units a US highway agency reads (ft, mph, ft-lb, ft², per mile
// mowed). Only what people read changes (the terminal's summary and the HTML page); the JSON
// and CSV files keep SI, named in their keys and headers, so that programs read one thing.
#include <fmt/format.h>
#include <string>
#include <string_view>

#include "scenario/input_error.hpp"

namespace j232::report {

struct DisplayUnits {
  bool us = false;

  // Exact conversions (the international foot, mile and pound-force).
  static constexpr double kFoot = 0.3048;                  // m
  static constexpr double kMile = 1609.344;                // m
  static constexpr double kFootPound = 1.3558179483314004;  // J (ft·lbf)
  static constexpr double kMph = kMile / 3600.0;           // m/s

  double length(double m) const { return us ? m / kFoot : m; }
  const char* length_unit() const { return us ? "ft" : "m"; }
  double speed(double metres_per_second) const { return us ? metres_per_second / kMph : metres_per_second; }
  const char* speed_unit() const { return us ? "mph" : "m/s"; }
  // A travel speed: km/h in SI (as the scenario gives it), mph in US units.
  double travel(double metres_per_second) const { return us ? metres_per_second / kMph : 3.6 * metres_per_second; }
  const char* travel_unit() const { return us ? "mph" : "km/h"; }
  double energy(double joules) const { return us ? joules / kFootPound : joules; }
  const char* energy_unit() const { return us ? "ft-lb" : "J"; }
  double area(double m2) const { return us ? m2 / (kFoot * kFoot) : m2; }
  const char* area_unit() const { return us ? "ft2" : "m2"; }
  const char* area_unit_html() const { return us ? "ft&sup2;" : "m&sup2;"; }
  // Counts per length mowed: per km, or per mile.
  double per_mowed(double per_km) const { return us ? per_km * kMile / 1000.0 : per_km; }
  const char* mowed() const { return us ? "mile" : "km"; }
  // Counts per area: per m², or per ft².
  double per_area(double per_m2) const { return us ? per_m2 * kFoot * kFoot : per_m2; }
  // An input quoted back (a plane's distance, an energy, an area): as given in SI, to three
  // figures once converted.
  std::string figure(double converted) const { return us ? fmt::format("{:.3g}", converted) : fmt::format("{:g}", converted); }
};

// "si" or "us"; anything else is refused, naming the option.
inline DisplayUnits display_units(std::string_view name) {
  if (name == "si") return {false};
  if (name == "us") return {true};
  throw scenario::InputError("", std::nullopt, "--units", std::string(name), "\"si\" (m, m/s, J) or \"us\" (ft, mph, ft-lb)");
}

}  // namespace j232::report
