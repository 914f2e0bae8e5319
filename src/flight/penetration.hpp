#pragma once
// How deep a slender steel projectile arriving point-first sinks into soil: Young's
// penetration equation (C. W. Young, "Penetration equations", Sandia report SAND97-2426,
// 1997) in its English units (D ft, W lb, A in^2, V ft/s), converted here exactly:
//   D = 0.3 S N K (W/A)^0.7 ln(1 + 2e-5 V^2)      for V < 200 ft/s,
//   D = 0.00178 S N K (W/A)^0.7 (V - 100)          above (the two meet at 200 ft/s),
// S the soil's penetrability number, N the nose's performance coefficient (a cone: 0.56 +
// 0.25 L_n/d), K = 0.4 W^0.15 the correction for a light penetrator (W < 400 lb), A the
// cross-section. Young's data are of penetrators of kilograms and more: for a 2 g nail this
// is an extrapolation, and is so labelled (docs/model.md §5.3a). The constants are as
// recalled, not checked against the report here; the branches' meeting is tested.
#include <algorithm>
#include <cmath>

namespace j232::flight {

// A nail's diamond point, about 1.5 shank diameters long (an estimate): N = 0.56 + 0.25 * 1.5.
inline constexpr double kNailNoseCoefficient = 0.56 + 0.25 * 1.5;

inline double young_depth(double penetrability, double mass, double diameter, double speed,
                          double nose = kNailNoseCoefficient) {
  if (!(penetrability > 0) || !(speed > 0) || !(mass > 0) || !(diameter > 0)) return 0.0;
  constexpr double kPound = 0.45359237, kInch = 0.0254, kFoot = 0.3048;  // kg, m, m
  const double weight = mass / kPound, area = 0.25 * 3.14159265358979323846 * diameter * diameter / (kInch * kInch);
  const double fps = speed / kFoot;
  const double light = 0.4 * std::pow(std::min(weight, 400.0), 0.15);
  const double scale = penetrability * nose * light * std::pow(weight / area, 0.7);
  const double feet = fps < 200.0 ? 0.3 * scale * std::log1p(2e-5 * fps * fps) : 0.00178 * scale * (fps - 100.0);
  return feet * kFoot;
}

}  // namespace j232::flight
