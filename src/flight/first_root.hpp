#pragma once
// The first non-negative root of a quadratic, in the form the contact searches meet it: when a
// height c0 > 0 above a plane, falling at rate c1 with acceleration c2, first reaches zero.
#include <cmath>

namespace j232::flight {

// The first x >= 0 at which c0 + c1 x + c2 x^2 / 2 (c0 > 0) reaches zero, or HUGE_VAL.
inline double first_root(double c0, double c1, double c2) {
  if (c2 == 0) return c1 < 0 ? -c0 / c1 : HUGE_VAL;
  const double disc = c1 * c1 - 2 * c2 * c0;
  if (disc < 0) return HUGE_VAL;
  // The roots' product is 2 c0 / c2 and sum -2 c1 / c2; stable forms of both.
  const double qq = -(c1 + std::copysign(std::sqrt(disc), c1));
  const double r1 = qq / c2, r2 = qq != 0 ? 2 * c0 / qq : HUGE_VAL;
  double best = HUGE_VAL;
  for (const double r : {r1, r2})
    if (r >= 0 && r < best) best = r;
  return best;
}

}  // namespace j232::flight
