#include "assess/statistics.hpp"

#include <algorithm>
#include <cmath>

#include "invariant/check.hpp"

namespace j232::assess {

Interval wilson(std::uint64_t k, std::uint64_t n, double z) {
  if (n == 0) return {0, 0, 1};
  const double nn = static_cast<double>(n), p = static_cast<double>(k) / nn, z2 = z * z;
  const double centre = (p + z2 / (2 * nn)) / (1 + z2 / nn);
  const double half = z / (1 + z2 / nn) * std::sqrt(p * (1 - p) / nn + z2 / (4 * nn * nn));
  // At k = 0 (k = n) the bound is 0 (1) exactly; computed, it is off by rounding (1e-19).
  return {p, k == 0 ? 0.0 : std::max(0.0, centre - half), k == n ? 1.0 : std::min(1.0, centre + half)};
}

Interval newcombe_independent(std::uint64_t k1, std::uint64_t n1, std::uint64_t k2, std::uint64_t n2, double z) {
  if (n1 == 0 || n2 == 0) return {0, -1, 1};
  const Interval first = wilson(k1, n1, z), second = wilson(k2, n2, z);
  const double d = second.estimate - first.estimate;
  return {d, d - std::hypot(second.estimate - second.low, first.high - first.estimate),
          d + std::hypot(second.high - second.estimate, first.estimate - first.low)};
}

Interval newcombe_paired(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t d, double z) {
  const std::uint64_t n = a + b + c + d;
  if (n == 0) return {0, -1, 1};
  const Interval first = wilson(a + b, n, z), second = wilson(a + c, n, z);
  const double p1 = first.estimate, p2 = second.estimate, delta = p2 - p1;
  // The phi coefficient of the 2 x 2 table; 0 when a margin is empty.
  const double margins = static_cast<double>(a + b) * static_cast<double>(c + d) * static_cast<double>(a + c) * static_cast<double>(b + d);
  const double phi = margins > 0 ? (static_cast<double>(a) * static_cast<double>(d) - static_cast<double>(b) * static_cast<double>(c)) / std::sqrt(margins)
                                 : 0.0;
  const double dl2 = p2 - second.low, du1 = first.high - p1, du2 = second.high - p2, dl1 = p1 - first.low;
  const double low = delta - std::sqrt(std::max(0.0, dl2 * dl2 - 2 * phi * dl2 * du1 + du1 * du1));
  const double high = delta + std::sqrt(std::max(0.0, du2 * du2 - 2 * phi * du2 * dl1 + dl1 * dl1));
  return {delta, std::max(-1.0, low), std::min(1.0, high)};
}

double quantile_sorted(const std::vector<double>& v, double p) {
  if (v.empty()) return 0;
  const double h = (static_cast<double>(v.size()) - 1) * p;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const auto hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

void Histogram::add(double v) {
  const double b = std::max(0.0, (v - origin) / bin_width);
  const auto i = std::min(static_cast<std::size_t>(b), counts.size() - 1);
  ++counts[i];
  ++total;
  sum += v;
}

void Histogram::merge(const Histogram& o) {
  J232_CHECK(o.counts.size() == counts.size() && o.bin_width == bin_width && o.origin == origin);  // the same bins
  for (std::size_t i = 0; i < counts.size(); ++i) counts[i] += o.counts[i];
  total += o.total;
  sum += o.sum;
}

double Histogram::quantile(double p) const {
  if (total == 0) return 0;
  const double target = p * static_cast<double>(total);
  double below = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const double c = static_cast<double>(counts[i]);
    if (below + c >= target && c > 0) return origin + bin_width * (static_cast<double>(i) + (target - below) / c);
    below += c;
  }
  return origin + bin_width * static_cast<double>(counts.size());
}

}  // namespace j232::assess
