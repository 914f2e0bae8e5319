#include "units/quantity.hpp"

#include <array>
#include <charconv>
#include <cctype>
#include <cmath>
#include <fmt/format.h>

namespace j232::units {
namespace {

struct NamedUnit {
  std::string_view name;
  double factor;
  Dimension dimension;
};

constexpr Dimension kMass{1, 0, 0, 0}, kLength{0, 1, 0, 0}, kTime{0, 0, 1, 0}, kNone{0, 0, 0, 0};
constexpr Dimension kAngle{0, 0, 0, 1}, kForce{1, 1, -2, 0}, kEnergy{1, 2, -2, 0}, kSpeed{0, 1, -1, 0};
constexpr Dimension kAngularSpeed{0, 0, -1, 1};

// The table is small on purpose: the units that mower data sheets, the report and
// handbooks use. An unknown unit is an error, never a guess.
constexpr std::array kUnits{
    NamedUnit{"m", 1.0, kLength},
    NamedUnit{"mm", 1e-3, kLength},
    NamedUnit{"cm", 1e-2, kLength},
    NamedUnit{"km", 1e3, kLength},
    NamedUnit{"in", inch, kLength},
    NamedUnit{"ft", foot, kLength},
    NamedUnit{"yd", 0.9144, kLength},
    NamedUnit{"mi", 1609.344, kLength},
    NamedUnit{"kg", 1.0, kMass},
    NamedUnit{"g", gram, kMass},
    NamedUnit{"mg", 1e-6, kMass},
    NamedUnit{"lb", pound, kMass},
    NamedUnit{"oz", pound / 16.0, kMass},
    NamedUnit{"gr", pound / 7000.0, kMass},
    NamedUnit{"s", 1.0, kTime},
    NamedUnit{"ms", 1e-3, kTime},
    NamedUnit{"min", 60.0, kTime},
    NamedUnit{"h", 3600.0, kTime},
    NamedUnit{"rad", 1.0, kAngle},
    NamedUnit{"deg", pi / 180.0, kAngle},
    NamedUnit{"rev", 2.0 * pi, kAngle},
    NamedUnit{"rpm", rpm, kAngularSpeed},
    NamedUnit{"mph", mph, kSpeed},
    NamedUnit{"N", 1.0, kForce},
    NamedUnit{"lbf", 4.4482216152605, kForce},
    NamedUnit{"J", 1.0, kEnergy},
    NamedUnit{"%", 0.01, kNone},
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// Exponents are small whole numbers in any real unit ("kg m^2", "m/s^2"); bounding
// them keeps the dimension arithmetic far from integer overflow and the factor finite.
constexpr int kMaxExponent = 12;

Dimension scaled(Dimension d, int power) { return {d.mass * power, d.length * power, d.time * power, d.angle * power}; }
Dimension plus(Dimension a, Dimension b) { return {a.mass + b.mass, a.length + b.length, a.time + b.time, a.angle + b.angle}; }
bool bounded(Dimension d) {
  for (int e : {d.mass, d.length, d.time, d.angle})
    if (e < -kMaxExponent * 4 || e > kMaxExponent * 4) return false;
  return true;
}

UnitValue named(std::string_view name, std::string_view whole) {
  for (const auto& u : kUnits)
    if (u.name == name) return {u.factor, u.dimension};
  throw UnitError(
      fmt::format("unknown unit \"{}\" in \"{}\" (known: m mm cm km in ft yd mi, kg g mg lb oz gr, s ms min h, "
                  "rad deg rev rpm, mph, N lbf J, %)",
                  name, whole));
}

}  // namespace

Dimension dimension_of(Kind kind) {
  switch (kind) {
    case Kind::Dimensionless: return kNone;
    case Kind::Angle: return kAngle;
    case Kind::Length: return kLength;
    case Kind::Mass: return kMass;
    case Kind::Time: return kTime;
    case Kind::Speed: return kSpeed;
    case Kind::AngularSpeed: return kAngularSpeed;
    case Kind::Inertia: return {1, 2, 0, 0};
    case Kind::Energy: return kEnergy;
    case Kind::EnergyPerLength: return {1, 1, -2, 0};
    case Kind::Acceleration: return {0, 1, -2, 0};
    case Kind::Density: return {1, -3, 0, 0};
    case Kind::Area: return {0, 2, 0, 0};
    case Kind::PerArea: return {0, -2, 0, 0};
  }
  return kNone;
}

std::string_view describe(Kind kind) {
  switch (kind) {
    case Kind::Dimensionless: return "a plain number such as 0.9";
    case Kind::Angle: return "an angle such as \"30 deg\"";
    case Kind::Length: return "a length such as \"24 in\" or \"0.6 m\"";
    case Kind::Mass: return "a mass such as \"22 lb\" or \"170 g\"";
    case Kind::Time: return "a time such as \"0.5 s\"";
    case Kind::Speed: return "a speed such as \"440 ft/min\" or \"5 mph\"";
    case Kind::AngularSpeed: return "an angular speed such as \"1000 rpm\" or \"104.7 rad/s\"";
    case Kind::Inertia: return "a moment of inertia such as \"0.05 kg m^2\" or \"1.2 lb ft^2\"";
    case Kind::Energy: return "an energy such as \"2.5 J\"";
    case Kind::EnergyPerLength: return "an energy per length such as \"110 J/m\"";
    case Kind::Acceleration: return "an acceleration such as \"9.81 m/s^2\"";
    case Kind::Density: return "a density such as \"1.2 kg/m^3\"";
    case Kind::Area: return "an area such as \"0.58 m^2\" or \"600 ft^2\"";
    case Kind::PerArea: return "a number per area such as \"0.5 m^-2\" or \"0.05 ft^-2\"";
  }
  return "a quantity";
}

UnitValue parse_unit(std::string_view expression) {
  const std::string_view whole = expression;
  UnitValue result;
  bool divide = false;
  bool expect_factor = true;
  std::size_t i = 0;
  while (i < expression.size()) {
    const char c = expression[i];
    if (c == ' ' || c == '\t') {
      ++i;
      continue;
    }
    if (c == '*' || c == '/') {
      if (expect_factor) throw UnitError(fmt::format("misplaced '{}' in unit \"{}\"", c, whole));
      divide = (c == '/');
      expect_factor = true;
      ++i;
      continue;
    }
    // A unit name: letters or '%'.
    std::size_t j = i;
    while (j < expression.size() && (std::isalpha(static_cast<unsigned char>(expression[j])) || expression[j] == '%')) ++j;
    if (j == i) throw UnitError(fmt::format("unexpected '{}' in unit \"{}\"", c, whole));
    UnitValue u = named(expression.substr(i, j - i), whole);
    int power = 1;
    if (j < expression.size() && expression[j] == '^') {
      ++j;
      const char* first = expression.data() + j;
      const char* last = expression.data() + expression.size();
      auto [ptr, ec] = std::from_chars(first, last, power);
      if (ec != std::errc() || power == 0 || power < -kMaxExponent || power > kMaxExponent)
        throw UnitError(fmt::format("bad exponent in unit \"{}\" (expected a non-zero whole number from -{} to {} after '^')", whole,
                                    kMaxExponent, kMaxExponent));
      j = static_cast<std::size_t>(ptr - expression.data());
    }
    if (divide) power = -power;
    result.factor *= std::pow(u.factor, power);
    result.dimension = plus(result.dimension, scaled(u.dimension, power));
    if (!bounded(result.dimension) || !std::isfinite(result.factor) || result.factor == 0.0)
      throw UnitError(fmt::format("unit \"{}\" is out of any physical range", whole));
    divide = false;  // '/' binds to the next factor only: "kg/m s" is kg s / m
    expect_factor = false;
    i = j;
  }
  if (expect_factor && !whole.empty()) throw UnitError(fmt::format("unit \"{}\" ends with an operator", whole));
  return result;
}

double parse(std::string_view text, Kind kind) {
  const std::string_view s = trim(text);
  double number = 0.0;
  const char* first = s.data();
  const char* last = s.data() + s.size();
  if (first != last && *first == '+') ++first;  // from_chars does not take a leading '+'
  auto [ptr, ec] = std::from_chars(first, last, number);
  if (ec != std::errc() || s.empty())
    throw UnitError(fmt::format("\"{}\" does not start with a number; expected {}", text, describe(kind)));
  if (!std::isfinite(number)) throw UnitError(fmt::format("\"{}\" is not a finite number", text));
  const std::string_view unit = trim(std::string_view(ptr, static_cast<std::size_t>(last - ptr)));
  if (unit.empty()) {
    if (kind == Kind::Dimensionless) return number;
    throw UnitError(fmt::format("\"{}\" has no unit; expected {}", text, describe(kind)));
  }
  const UnitValue u = parse_unit(unit);
  if (!(u.dimension == dimension_of(kind)))
    throw UnitError(fmt::format("\"{}\" has the wrong kind of unit; expected {}", text, describe(kind)));
  const double value = number * u.factor;
  if (!std::isfinite(value)) throw UnitError(fmt::format("\"{}\" is not a finite number in SI units", text));
  return value;
}

}  // namespace j232::units
