#include "assess/exact_pass.hpp"

#include <algorithm>
#include <boost/random/gamma_distribution.hpp>
#include <cmath>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "assess/statistics.hpp"
#include "random/stream.hpp"

namespace j232::assess {

std::uint32_t marks_key(const flight::FlightResult& nail) {
  const auto cap = [](int n) { return static_cast<std::uint32_t>(std::clamp(n, 0, 255)); };
  return cap(nail.hits_zone) | cap(nail.punctures_zone) << 8 | cap(nail.hits_outside) << 16 | cap(nail.punctures_outside) << 24;
}

NailMarks marks_of_key(std::uint32_t key) {
  return {static_cast<int>(key & 0xFFu), static_cast<int>(key >> 8 & 0xFFu), static_cast<int>(key >> 16 & 0xFFu),
          static_cast<int>(key >> 24 & 0xFFu)};
}

void StationOutcomes::add(int station, std::uint32_t key) {
  const auto s = static_cast<std::size_t>(station);
  if (by_station.size() <= s) by_station.resize(s + 1);
  ++by_station[s][key];
}

void StationOutcomes::merge(const StationOutcomes& other) {
  if (by_station.size() < other.by_station.size()) by_station.resize(other.by_station.size());
  for (std::size_t s = 0; s < other.by_station.size(); ++s)
    for (const auto& [key, n] : other.by_station[s]) by_station[s][key] += n;
}

std::uint64_t StationOutcomes::nails(std::size_t station) const {
  std::uint64_t n = 0;
  if (station < by_station.size())
    for (const auto& [key, count] : by_station[station]) n += count;
  return n;
}

int allowed_count(const scenario::CriteriaSpec& criteria, int category, int nails) {
  // judge(): count / nails <= limit + 1e-12.
  const double limit = category_limit(criteria, category) + 1e-12;
  int k = static_cast<int>(std::floor(limit * nails));
  while (k + 1 <= nails && static_cast<double>(k + 1) / nails <= limit) ++k;
  while (k >= 0 && static_cast<double>(k) / nails > limit) --k;
  return std::min(k, nails);
}

double pass_probability(const std::vector<OutcomeDistribution>& stations, int nails, const std::array<int, kCategories>& allowed) {
  constexpr double kNegligible = 1e-15;
  std::array<int, kCategories> dim{};
  std::size_t states = 1;
  for (int c = 0; c < kCategories; ++c) {
    if (allowed[static_cast<std::size_t>(c)] < 0) return 0.0;  // not even a clean test passes
    dim[static_cast<std::size_t>(c)] = allowed[static_cast<std::size_t>(c)] + 1;
    states *= static_cast<std::size_t>(dim[static_cast<std::size_t>(c)]);
  }
  // Strides of the flattened count vector (a, b, c, d), d contiguous.
  const std::array<std::size_t, kCategories> stride{static_cast<std::size_t>(dim[1] * dim[2] * dim[3]), static_cast<std::size_t>(dim[2] * dim[3]),
                                                    static_cast<std::size_t>(dim[3]), 1};
  const auto at = [&](int a, int b, int c) {
    return static_cast<std::size_t>(a) * stride[0] + static_cast<std::size_t>(b) * stride[1] + static_cast<std::size_t>(c) * stride[2];
  };
  std::vector<double> mass(states, 0.0), next(states, 0.0);
  mass[0] = 1.0;
  // The probability held by the counts from lo to hi (inclusive) in every category.
  const auto box_sum = [&](const std::array<int, kCategories>& lo, const std::array<int, kCategories>& hi) {
    double sum = 0;
    for (int a = lo[0]; a <= hi[0]; ++a)
      for (int b = lo[1]; b <= hi[1]; ++b)
        for (int c = lo[2]; c <= hi[2]; ++c)
          for (int e = lo[3]; e <= hi[3]; ++e) sum += mass[at(a, b, c) + static_cast<std::size_t>(e)];
    return sum;
  };
  // Counts reached so far in each category: the loops need go no further.
  std::array<int, kCategories> reach{};
  for (int i = 0; i < nails; ++i) {
    const OutcomeDistribution& d = stations[static_cast<std::size_t>(i) % stations.size()];
    std::array<int, kCategories> grown{};
    for (const auto& [o, p] : d)
      for (std::size_t c = 0; c < kCategories; ++c)
        if (o[c] <= allowed[c]) grown[c] = std::max(grown[c], std::min(allowed[c], reach[c] + o[c]));
    // Clear the box the new counts may reach, then add each outcome's shifted copy of the
    // box reached so far (the part of it that stays within the limits; the rest fails).
    for (int a = 0; a <= grown[0]; ++a)
      for (int b = 0; b <= grown[1]; ++b)
        for (int c = 0; c <= grown[2]; ++c) {
          double* row = &next[at(a, b, c)];
          std::fill(row, row + grown[3] + 1, 0.0);
        }
    for (const auto& [o, p] : d) {
      std::array<int, kCategories> top{};
      bool fits = true;
      for (std::size_t c = 0; c < kCategories; ++c) {
        top[c] = std::min(reach[c], allowed[c] - o[c]);
        fits = fits && top[c] >= 0;
      }
      if (!fits) continue;
      const std::size_t shift = at(o[0], o[1], o[2]) + static_cast<std::size_t>(o[3]);
      const double w = p;
      for (int a = 0; a <= top[0]; ++a)
        for (int b = 0; b <= top[1]; ++b)
          for (int c = 0; c <= top[2]; ++c) {
            const double* from = &mass[at(a, b, c)];
            double* to = &next[at(a, b, c) + shift];
            for (int e = 0; e <= top[3]; ++e) to[e] += w * from[e];
          }
    }
    reach = grown;
    mass.swap(next);
    // Counts reached only with a vanishing probability are left out of the box (their tests
    // counted as failing): each slice left out held at most kNegligible, so P(pass) comes out
    // low by at most that per slice (under 1e-11 in all for 150 nails that mark a few times
    // each), and the box stays the counts that matter (an operator-zone hit at 1 in 10 000
    // nails never needs 30 of them): 4-5 times fewer states on the shipped scenarios.
    for (std::size_t k = 0; k < kCategories; ++k)
      while (reach[k] > 0) {
        std::array<int, kCategories> lo{};  // the slice of the box at its largest count of k
        lo[k] = reach[k];
        if (box_sum(lo, reach) > kNegligible) break;
        --reach[k];
      }
  }
  return std::min(1.0, box_sum({}, reach));
}

ExactPass exact_pass(const StationOutcomes& outcomes, int nails, const scenario::CriteriaSpec& criteria, std::uint64_t seed, int draws,
                     std::uint64_t max_states) {
  ExactPass out;
  if (criteria.denominator == scenario::CriteriaSpec::Denominator::Marks) {
    out.not_computed = "the shares are of all marks (criteria.denominator = \"marks\"): the exact estimate needs the total as one more count";
    return out;
  }
  const std::size_t S = outcomes.by_station.size();
  if (S == 0 || nails <= 0) {
    out.not_computed = "no nail was recorded";
    return out;
  }
  for (std::size_t s = 0; s < S; ++s)
    if (outcomes.nails(s) == 0 && s < static_cast<std::size_t>(nails)) {
      out.not_computed = fmt::format("no nail was recorded at feed station {}", s + 1);
      return out;
    }
  std::array<int, kCategories> allowed{};
  std::uint64_t states = 1;
  for (int c = 0; c < kCategories; ++c) {
    allowed[static_cast<std::size_t>(c)] = allowed_count(criteria, c, nails);
    states *= static_cast<std::uint64_t>(std::max(allowed[static_cast<std::size_t>(c)], 0) + 1);
  }
  out.states = states;
  if (states > max_states) {
    out.not_computed = fmt::format("the limits allow {} combinations of counts (more than {}): too many to sum exactly", states, max_states);
    return out;
  }
  // The observed frequencies.
  std::vector<OutcomeDistribution> observed(S);
  for (std::size_t s = 0; s < S; ++s) {
    const double n = static_cast<double>(outcomes.nails(s));
    for (const auto& [key, count] : outcomes.by_station[s]) observed[s].push_back({marks_of_key(key), static_cast<double>(count) / n});
  }
  out.value = pass_probability(observed, nails, allowed);
  out.computed = true;
  out.draws = draws;
  if (draws <= 0) {
    out.low = out.high = out.value;
    return out;
  }
  // Bayesian bootstrap: each station's outcome probabilities drawn from Dirichlet(counts +
  // prior), the prior a quarter of a nail on each single mark (one nail in all: weak, but
  // it keeps a mark no nail made from being called impossible).
  constexpr double kPrior = 0.25;
  std::vector<std::vector<std::pair<NailMarks, double>>> alphas(S);
  for (std::size_t s = 0; s < S; ++s) {
    std::map<std::uint32_t, double> a;
    for (const auto& [key, count] : outcomes.by_station[s]) a[key] += static_cast<double>(count);
    for (int c = 0; c < kCategories; ++c) a[1u << (8 * c)] += kPrior;
    for (const auto& [key, alpha] : a) alphas[s].push_back({marks_of_key(key), alpha});
  }
  // Each draw from its own stream (keyed by the draw), in parallel: the same values on any
  // number of threads.
  std::vector<double> values(static_cast<std::size_t>(draws));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, values.size()), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<OutcomeDistribution> drawn(S);
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      random::Stream rng(seed, k, 0, random::Purpose::Estimator);
      for (std::size_t s = 0; s < S; ++s) {
        drawn[s].clear();
        double sum = 0;
        for (const auto& [o, alpha] : alphas[s]) {
          boost::random::gamma_distribution<double> gamma(alpha, 1.0);
          const double g = gamma(rng);
          drawn[s].push_back({o, g});
          sum += g;
        }
        for (auto& [o, w] : drawn[s]) w /= sum;
      }
      values[k] = pass_probability(drawn, nails, allowed);
    }
  });
  std::sort(values.begin(), values.end());
  out.low = std::min(quantile_sorted(values, 0.025), out.value);
  out.high = std::max(quantile_sorted(values, 0.975), out.value);
  return out;
}

}  // namespace j232::assess
