#pragma once
// sin and cos of one angle together, for the contact searches' many probes (the blade's
// frame and the nail's axis at each instant). The angle is reduced by multiples of pi/2
// split in three parts (Cody and Waite), exact for |x| < 2^29 pi/2, then the minimax
// polynomials of the Cephes library (S. L. Moshier, "Methods and Programs for
// Mathematical Functions", 1989) on [-pi/4, pi/4]: within 2e-16 of the library's sin and
// cos for the angles a search meets (|x| up to 1e6 rad; tests/test_units.cpp), at a third
// of their cost, inlined.
#include <cmath>

namespace j232::units {

struct SinCos {
  double sin = 0, cos = 1;
};

inline SinCos sin_cos(double x) {
  constexpr double kTwoOverPi = 0.63661977236758134308;
  constexpr double kPi2a = 2 * 7.85398125648498535156e-1, kPi2b = 2 * 3.77489470793079817668e-8, kPi2c = 2 * 2.69515142907905952645e-15;
  const double j = std::nearbyint(x * kTwoOverPi);
  const double y = ((x - j * kPi2a) - j * kPi2b) - j * kPi2c;
  const double z = y * y;
  const double s = y + y * z * (((((1.58962301576546568060e-10 * z - 2.50507477628578072866e-8) * z + 2.75573136213857245213e-6) * z -
                                  1.98412698295895385996e-4) * z + 8.33333333332211858878e-3) * z - 1.66666666666666307295e-1);
  const double c = 1.0 - 0.5 * z + z * z * (((((-1.13585365213876817300e-11 * z + 2.08757008419747316778e-9) * z - 2.75573141792967388112e-7) * z +
                                             2.48015872888517045348e-5) * z - 1.38888888888730564116e-3) * z + 4.16666666666665929218e-2);
  switch (static_cast<long long>(j) & 3) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case 2: return {-s, -c};
    default: return {-c, s};
  }
}

}  // namespace j232::units
