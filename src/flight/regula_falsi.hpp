#pragma once
// The contact searches' last step: a bracketed root brought in by regula falsi with the
// Illinois modification (the end that stays put has its value halved, so the bracket closes
// from both sides).

namespace j232::flight {

// A root of g in [lo, hi], with g(lo) = g_lo > 0 >= g(hi) = g_hi: iterates until the bracket is
// narrow enough, `max_iterations` have run, or `accept(mid, g(mid))` takes a point;
// returns that point, or else the bracket's end where g <= 0. The bracket's width is measured
// as (hi - lo) * rate against `tolerance` (a time bracket, the fastest motion, a distance).
template <class G, class Accept>
double illinois_root(double lo, double g_lo, double hi, double g_hi, G&& g, double rate, double tolerance, int max_iterations,
                     Accept&& accept) {
  int side = 0;
  for (int it = 0; it < max_iterations && (hi - lo) * rate > tolerance; ++it) {
    double mid = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
    if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
    const double g_mid = g(mid);
    if (accept(mid, g_mid)) return mid;
    if (g_mid > 0) {
      lo = mid, g_lo = g_mid;
      if (side == -1) g_hi *= 0.5;
      side = -1;
    } else {
      hi = mid, g_hi = g_mid;
      if (side == 1) g_lo *= 0.5;
      side = 1;
    }
  }
  return hi;
}

}  // namespace j232::flight
