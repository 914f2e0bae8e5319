#pragma once
// Goodness-of-fit helpers for statistical tests of samplers.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace j232::test {

// One-sample Kolmogorov-Smirnov statistic D against a continuous CDF.
inline double ks_statistic(std::vector<double> x, const std::function<double(double)>& cdf) {
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  double d = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = cdf(x[i]);
    d = std::max({d, static_cast<double>(i + 1) / n - f, f - static_cast<double>(i) / n});
  }
  return d;
}

// Critical D at significance alpha = 0.001 (asymptotic: 1.949 / sqrt(n)). A correct
// sampler fails this one time in a thousand; the seeds are fixed, so a test that
// passes once passes always.
inline double ks_critical_001(std::size_t n) { return 1.949 / std::sqrt(static_cast<double>(n)); }

}  // namespace j232::test
