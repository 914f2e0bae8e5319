#pragma once
// Small, exact statistics for Monte Carlo tallies.
#include <cstdint>
#include <vector>

namespace j232::assess {

struct Interval {
  double estimate = 0, low = 0, high = 0;
};

// Wilson score interval for k successes in n trials (z = 1.96 for 95 %). Well behaved at
// k = 0 and k = n, where the normal approximation collapses to zero width.
Interval wilson(std::uint64_t successes, std::uint64_t trials, double z = 1.959963984540054);

// The difference p2 - p1 of two proportions measured on the same n pairs (Newcombe 1998,
// "Improved confidence intervals for the difference between binomial proportions based on
// paired data", Statistics in Medicine 17, method 10): from the Wilson intervals of both
// and the correlation of the pairs. `both`: pairs with 1 in both; `only_first`, `only_second`:
// 1 in one only; `neither`. Never zero-wide, also when no pair differs (then it says how
// large a difference n pairs could have missed).
Interval newcombe_paired(std::uint64_t both, std::uint64_t only_first, std::uint64_t only_second, std::uint64_t neither,
                         double z = 1.959963984540054);

// The difference p2 - p1 of two proportions from independent samples, k1 of n1 and k2 of n2
// (Newcombe 1998, "Interval estimation for the difference between independent proportions:
// comparison of eleven methods", Statistics in Medicine 17, method 10: the hybrid score
// interval from both Wilson intervals).
Interval newcombe_independent(std::uint64_t k1, std::uint64_t n1, std::uint64_t k2, std::uint64_t n2, double z = 1.959963984540054);

// Quantile p of values (sorted ascending), linear interpolation between order
// statistics (Hyndman & Fan type 7, as R and NumPy by default).
double quantile_sorted(const std::vector<double>& sorted, double p);

// A fixed-bin histogram: merging is exact and order-free, so it is deterministic
// across threads; quantiles are read to within one bin.
struct Histogram {
  double bin_width = 1;
  double origin = 0;                  // the first bin's lower edge (everything below lands in it)
  std::vector<std::uint64_t> counts;  // last bin collects everything beyond
  std::uint64_t total = 0;
  double sum = 0;  // for the exact mean (summed per chunk, merged in chunk order)

  Histogram() = default;
  Histogram(double width, std::size_t bins, double lower_edge = 0) : bin_width(width), origin(lower_edge), counts(bins, 0) {}
  void add(double v);
  void merge(const Histogram& other);
  double mean() const { return total ? sum / static_cast<double>(total) : 0.0; }
  double quantile(double p) const;  // bin midpoint interpolation
};

// The largest of whole counts seen (a nail's pass of most contacts): merged by taking the
// larger, so it too is exact and order-free, and unlike a histogram's last bin it has no
// ceiling.
struct Largest {
  std::uint64_t value = 0;
  void add(std::uint64_t v) { value = v > value ? v : value; }
  void merge(const Largest& o) { add(o.value); }
};

}  // namespace j232::assess
