#include "study/compare.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace j232::study {

namespace {
constexpr double kZ = 1.959963984540054;

// Running sums for a mean and its spread, in replicate order (deterministic).
struct Moments {
  double n = 0, sum = 0, sum_sq = 0;
  void add(double x) { n += 1, sum += x, sum_sq += x * x; }
  double mean() const { return n > 0 ? sum / n : 0.0; }
  double variance() const { return n > 1 ? std::max(0.0, (sum_sq - sum * sum / n) / (n - 1)) : 0.0; }
  // Clipped to the values the quantity can take: [0, 1] for a share, [-1, 1] for a difference.
  MeanInterval interval(double lowest, double highest) const {
    const double half = n > 1 ? kZ * std::sqrt(variance() / n) : 0.0;
    return {mean(), std::max(lowest, mean() - half), std::min(highest, mean() + half)};
  }
};
}  // namespace

Comparison compare_designs(std::vector<scenario::Scenario> designs, int threads, assess::Progress* progress,
                           const std::function<void(std::size_t, const scenario::Scenario&)>& on_design) {
  if (designs.size() < 2) throw std::invalid_argument("a comparison needs at least two designs");
  Comparison c;
  c.seed = designs.front().run.seed;
  c.replicates = static_cast<std::uint64_t>(designs.front().run.replicates);
  // Per replicate, per design: the four shares and the pass (kept: 5 numbers per replicate).
  std::vector<std::vector<std::array<double, assess::kCategories + 1>>> per(designs.size());
  for (std::size_t d = 0; d < designs.size(); ++d) {
    scenario::Scenario& s = designs[d];
    s.run.seed = c.seed;
    s.run.replicates = static_cast<long long>(c.replicates);
    s.run.target_half_width.reset();
    if (on_design) on_design(d, s);
    per[d].resize(c.replicates);
    const assess::Simulator sim(s);
    const auto a = assess::run_assessment(sim, threads, progress, {}, [&](std::uint64_t r, const assess::Judgement& j) {
      for (int k = 0; k < assess::kCategories; ++k) per[d][r][static_cast<std::size_t>(k)] = j.shares[static_cast<std::size_t>(k)];
      per[d][r][assess::kCategories] = j.pass ? 1.0 : 0.0;
    });
    DesignResult res;
    res.file = s.file;
    res.title = s.title;
    res.pass = assess::wilson(a.passed, a.replicates);
    for (int k = 0; k < assess::kCategories; ++k) {
      Moments m;
      for (const auto& row : per[d]) m.add(row[static_cast<std::size_t>(k)]);
      res.shares[static_cast<std::size_t>(k)] = m.interval(0.0, 1.0);
    }
    res.limits = {s.criteria.hits_zone, s.criteria.punctures_zone, s.criteria.hits_outside, s.criteria.punctures_outside};
    res.marks = a.marks;
    res.nails = a.nails;
    c.designs.push_back(res);
  }
  for (std::size_t d = 1; d < designs.size(); ++d) {
    Difference diff;
    for (int k = 0; k <= assess::kCategories; ++k) {
      Moments paired, first, other;
      for (std::uint64_t r = 0; r < c.replicates; ++r) {
        const double a = per[0][r][static_cast<std::size_t>(k)], b = per[d][r][static_cast<std::size_t>(k)];
        paired.add(b - a);
        first.add(a);
        other.add(b);
      }
      const double n = static_cast<double>(c.replicates);
      const double independent = n > 1 ? kZ * std::sqrt((first.variance() + other.variance()) / n) : 0.0;
      if (k == assess::kCategories) {
        diff.pass = paired.interval(-1.0, 1.0);
        diff.independent_pass_half_width = independent;
      } else {
        diff.shares[static_cast<std::size_t>(k)] = paired.interval(-1.0, 1.0);
        diff.independent_half_width[static_cast<std::size_t>(k)] = independent;
      }
    }
    c.versus_first.push_back(diff);
  }
  return c;
}

}  // namespace j232::study
