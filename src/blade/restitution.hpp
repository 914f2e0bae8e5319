#pragma once
// Coefficient of restitution between the blade and the struck object.
// Report 445-1 uses a constant e (0.3 to 0.9; 0.90 to 0.92 in its lab). Steel on steel
// at 10 to 100 m/s is plastic and e falls with the approach speed; Johnson (Contact
// Mechanics, §11.4) gives e proportional to v^-1/4, which the power law expresses:
//     e(v) = min(e_max, coefficient * (v / reference_speed)^exponent).
#include <string>

namespace j232::blade {

struct Restitution {
  enum class Model { Constant, PowerLaw };
  Model model = Model::Constant;
  double e = 0.9;                // Constant
  double coefficient = 1.06;     // PowerLaw, at v = reference_speed
  double exponent = -0.25;       // PowerLaw
  double reference_speed = 1.0;  // m/s
  double maximum = 0.9;          // PowerLaw cap (low speeds)

  static Restitution constant(double e) { return {Model::Constant, e}; }
  static Restitution power_law(double coefficient, double exponent, double maximum, double reference_speed = 1.0) {
    return {Model::PowerLaw, 0.0, coefficient, exponent, reference_speed, maximum};
  }
  // The default law, steel nail on steel blade (docs/model.md §3): the members' defaults above.
  static Restitution default_power_law() {
    Restitution r;
    r.model = Model::PowerLaw;
    return r;
  }

  // e at a normal approach speed v > 0 (m/s); always within [0, 1].
  double at(double approach_speed) const;

  // Empty when sound, else what is wrong ("e must lie in [0, 1], got 1.2").
  std::string problem() const;
  std::string describe() const;  // "e = 0.9" or "e(v) = min(0.9, 1.06 (v / 1 m/s)^-0.25)"
};

}  // namespace j232::blade
