#pragma once
// Physical quantities written as text with units ("22 lb", "24 in", "1000 rpm",
// "440 ft/min", "0.004 lb ft^2") converted to SI. Everything inside j232 is SI
// (m, kg, s, rad); units live only at the edges: input files and reports.
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

namespace j232::units {

// Exponents of mass, length, time and plane angle. Angle is kept as its own
// dimension so that "30 deg" is refused where a restitution coefficient is
// expected and "1000 rpm" (rev/min) is an angular speed like "rad/s".
struct Dimension {
  int mass = 0, length = 0, time = 0, angle = 0;
  friend bool operator==(const Dimension&, const Dimension&) = default;
};

// The kinds of quantity a scenario asks for. Each names its dimension and an
// example a user can copy when they get it wrong.
enum class Kind { Dimensionless, Angle, Length, Mass, Time, Speed, AngularSpeed, Inertia, Energy, EnergyPerLength, Acceleration, Density, Area, PerArea };

Dimension dimension_of(Kind kind);
std::string_view describe(Kind kind);  // "a speed such as \"440 ft/min\""

// Thrown for text that is not a number followed by a known unit of the right kind.
// The message says what was wrong; callers add where it came from.
class UnitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses "<number> <unit expression>" and returns the value in SI.
// Unit expressions multiply with spaces or '*', divide with '/', and take
// integer powers with '^': "kg m^2", "lb*ft^2", "ft/min", "J/m".
// A bare number is accepted only for Dimensionless.
double parse(std::string_view text, Kind kind);

// SI value of one named unit or unit expression ("ft/min" -> 0.00508) and its dimension.
struct UnitValue {
  double factor = 1.0;
  Dimension dimension;
};
UnitValue parse_unit(std::string_view expression);

// Handy constants for code and tests.
inline constexpr double pi = 3.14159265358979323846;
inline constexpr double two_pi = 2 * pi;
inline constexpr double degree = pi / 180;           // rad: x degrees is x * degree; an angle in degrees is a / degree
inline constexpr double standard_gravity = 9.80665;  // m/s^2 (CGPM 1901), the one value of g in j232
inline constexpr double inch = 0.0254;
inline constexpr double foot = 0.3048;
inline constexpr double pound = 0.45359237;
inline constexpr double gram = 1e-3;
inline constexpr double rpm = 2.0 * pi / 60.0;
inline constexpr double ft_per_min = foot / 60.0;
inline constexpr double mph = 0.44704;

// An angle brought into [0, 2 pi).
inline double wrap_angle(double a) {
  a = std::fmod(a, two_pi);
  return a < 0 ? a + two_pi : a;
}

}  // namespace j232::units
