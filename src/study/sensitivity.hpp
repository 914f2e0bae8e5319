#pragma once
// Global sensitivity analysis by Sobol' indices (docs/model.md §6b): which uncertain input
// drives an output, alone (first order S_i) and with all its interactions (total S_Ti).
// The Saltelli scheme: two N x k matrices A and B of independent points in [0, 1)^k (from
// a Sobol' low-discrepancy sequence of dimension 2k) and, for each input i, AB_i = A with
// its column i from B: N (k + 2) model runs. Estimators (Saltelli et al. 2010, Table 2):
//   S_i  = mean_j[ f(B)_j (f(AB_i)_j - f(A)_j) ] / V
//   S_Ti = mean_j[ (f(A)_j - f(AB_i)_j)^2 ] / (2 V)          (Jansen 1999)
// with V the variance of f over A and B together; 95 % intervals by bootstrap over j.
#include <cstdint>
#include <vector>

namespace j232::study {

struct SaltelliDesign {
  std::size_t inputs = 0, base = 0;       // k, N
  std::vector<std::vector<double>> a, b;  // N rows of k numbers in [0, 1)
  // The points in run order: A rows, B rows, then AB_1 rows, ..., AB_k rows.
  std::vector<std::vector<double>> runs() const;
};

// The first N points of the 2k-dimensional Sobol' sequence (Boost.Random), skipping the
// origin: deterministic.
SaltelliDesign saltelli_design(std::size_t inputs, std::size_t base);

struct Index {
  double estimate = 0, low = 0, high = 0;
};
struct SobolIndices {
  double variance = 0;
  std::vector<Index> first, total;  // one per input
};

// `outputs` in the order of SaltelliDesign::runs(). Bootstrap: `resamples` resamplings of
// the N base rows, from a fixed `seed`.
SobolIndices sobol_indices(const SaltelliDesign& design, const std::vector<double>& outputs, int resamples = 500, std::uint64_t seed = 1);

// The same from the design's first `base` base draws only (a prefix of the Sobol' sequence
// is itself a design): the indices at N/2 beside those at N show whether N is enough.
SobolIndices sobol_indices_prefix(const SaltelliDesign& design, const std::vector<double>& outputs, std::size_t base, int resamples = 500,
                                  std::uint64_t seed = 1);

// Whether an index's interval leaves [0, 1], where an index lies, by more than
// kUnitSlack: at that N the estimate is as much the estimator's noise as the input's
// effect. (An interval reaching a little below 0 is what an index near 0 shows at any N.)
inline constexpr double kUnitSlack = 0.05;
inline bool leaves_unit_interval(const Index& i) { return i.low < -kUnitSlack || i.high > 1.0 + kUnitSlack; }

}  // namespace j232::study
