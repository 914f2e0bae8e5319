#include "study/sensitivity.hpp"

#include <algorithm>
#include <boost/random/mersenne_twister.hpp>
#include <boost/random/sobol.hpp>
#include <boost/random/uniform_int_distribution.hpp>
#include <stdexcept>

namespace j232::study {

std::vector<std::vector<double>> SaltelliDesign::runs() const {
  std::vector<std::vector<double>> out(a);
  out.insert(out.end(), b.begin(), b.end());
  for (std::size_t i = 0; i < inputs; ++i)
    for (std::size_t j = 0; j < base; ++j) {
      auto row = a[j];
      row[i] = b[j][i];
      out.push_back(row);
    }
  return out;
}

SaltelliDesign saltelli_design(std::size_t inputs, std::size_t base) {
  if (inputs == 0 || base < 2) throw std::invalid_argument("a Saltelli design needs at least one input and two base points");
  SaltelliDesign d;
  d.inputs = inputs;
  d.base = base;
  boost::random::sobol gen(2 * inputs);
  gen.discard(2 * inputs);  // the first point is the origin: skip it
  for (std::size_t j = 0; j < base; ++j) {
    std::vector<double> point(2 * inputs);
    for (auto& x : point) x = static_cast<double>(gen() >> 11) * 0x1p-53;
    d.a.emplace_back(point.begin(), point.begin() + static_cast<std::ptrdiff_t>(inputs));
    d.b.emplace_back(point.begin() + static_cast<std::ptrdiff_t>(inputs), point.end());
  }
  return d;
}

namespace {
// The indices from the rows `rows` (a bootstrap resample, or 0..N-1).
void estimate(const SaltelliDesign& d, const std::vector<double>& f, const std::vector<std::size_t>& rows, double& variance,
              std::vector<double>& first, std::vector<double>& total) {
  const std::size_t n = d.base, k = d.inputs;
  double sum = 0, sum_sq = 0;
  for (std::size_t j : rows) {
    for (double v : {f[j], f[n + j]}) sum += v, sum_sq += v * v;
  }
  const double m = 2.0 * static_cast<double>(rows.size());
  variance = std::max(0.0, sum_sq / m - (sum / m) * (sum / m));
  first.assign(k, 0.0);
  total.assign(k, 0.0);
  for (std::size_t i = 0; i < k; ++i) {
    double s = 0, t = 0;
    for (std::size_t j : rows) {
      const double fa = f[j], fb = f[n + j], fab = f[(2 + i) * n + j];
      s += fb * (fab - fa);
      t += (fa - fab) * (fa - fab);
    }
    const double count = static_cast<double>(rows.size());
    first[i] = variance > 0 ? s / count / variance : 0.0;
    total[i] = variance > 0 ? t / (2 * count) / variance : 0.0;
  }
}

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const double h = (static_cast<double>(v.size()) - 1) * p;
  const auto lo = static_cast<std::size_t>(h);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}
}  // namespace

SobolIndices sobol_indices(const SaltelliDesign& d, const std::vector<double>& f, int resamples, std::uint64_t seed) {
  if (f.size() != d.base * (d.inputs + 2)) throw std::invalid_argument("expected one output per run of the design");
  SobolIndices out;
  std::vector<std::size_t> rows(d.base);
  for (std::size_t j = 0; j < d.base; ++j) rows[j] = j;
  std::vector<double> first, total;
  estimate(d, f, rows, out.variance, first, total);
  std::vector<std::vector<double>> boot_first(d.inputs), boot_total(d.inputs);
  boost::random::mt19937_64 rng(seed);
  boost::random::uniform_int_distribution<std::size_t> pick(0, d.base - 1);
  std::vector<double> bf, bt;
  double bv = 0;
  for (int r = 0; r < resamples; ++r) {
    for (auto& j : rows) j = pick(rng);
    estimate(d, f, rows, bv, bf, bt);
    for (std::size_t i = 0; i < d.inputs; ++i) boot_first[i].push_back(bf[i]), boot_total[i].push_back(bt[i]);
  }
  for (std::size_t i = 0; i < d.inputs; ++i) {
    Index s{first[i], first[i], first[i]}, t{total[i], total[i], total[i]};
    if (resamples > 1) {
      s.low = percentile(boot_first[i], 0.025), s.high = percentile(boot_first[i], 0.975);
      t.low = percentile(boot_total[i], 0.025), t.high = percentile(boot_total[i], 0.975);
    }
    out.first.push_back(s);
    out.total.push_back(t);
  }
  return out;
}

SobolIndices sobol_indices_prefix(const SaltelliDesign& d, const std::vector<double>& f, std::size_t base, int resamples, std::uint64_t seed) {
  SaltelliDesign prefix;
  prefix.inputs = d.inputs;
  prefix.base = std::min(base, d.base);
  prefix.a.assign(d.a.begin(), d.a.begin() + static_cast<std::ptrdiff_t>(prefix.base));
  prefix.b.assign(d.b.begin(), d.b.begin() + static_cast<std::ptrdiff_t>(prefix.base));
  std::vector<double> g;
  for (std::size_t block = 0; block < d.inputs + 2; ++block)
    for (std::size_t j = 0; j < prefix.base; ++j) g.push_back(f[block * d.base + j]);
  return sobol_indices(prefix, g, resamples, seed);
}

}  // namespace j232::study
