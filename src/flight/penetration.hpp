#pragma once
// How deep a slender steel projectile arriving point-first sinks into soil: Young's
// penetration equation (C. W. Young, "Penetration equations", Sandia report SAND97-2426,
// 1997), in SI units:
//   D = 0.0008 S N K (m/A)^0.7 ln(1 + 2.15e-4 V^2)    for V < 61 m/s,
//   D = 0.000018 S N K (m/A)^0.7 (V - 30.5)             above,
// S the soil's penetrability number, N the nose's performance coefficient (a cone: 0.56 +
// 0.25 L_n/d), K = 0.46 m^0.15 the correction for a light penetrator (m < 182 kg), A the
// cross-section. Young's data are of penetrators of kilograms and more: for a 2 g nail this
// is an extrapolation, and is so labelled (docs/model.md §5.3a).
#include <algorithm>
#include <cmath>

namespace j232::flight {

// A nail's diamond point, about 1.5 shank diameters long (an estimate): N = 0.56 + 0.25 * 1.5.
inline constexpr double kNailNoseCoefficient = 0.56 + 0.25 * 1.5;

inline double young_depth(double penetrability, double mass, double diameter, double speed,
                          double nose = kNailNoseCoefficient) {
  if (!(penetrability > 0) || !(speed > 0) || !(mass > 0) || !(diameter > 0)) return 0.0;
  const double area = 0.25 * 3.14159265358979323846 * diameter * diameter;
  const double light = 0.46 * std::pow(std::min(mass, 182.0), 0.15);
  const double scale = penetrability * nose * light * std::pow(mass / area, 0.7);
  return speed < 61.0 ? 0.0008 * scale * std::log1p(2.15e-4 * speed * speed) : 0.000018 * scale * (speed - 30.5);
}

}  // namespace j232::flight
