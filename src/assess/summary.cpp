#include "assess/summary.hpp"

#include <algorithm>

namespace j232::assess {

Summary summarise(const Assessment& a, const scenario::CriteriaSpec& criteria) {
  Summary s;
  s.replicates = a.tallies.size();
  s.nails = a.nails;
  s.struck = a.struck;
  s.required = criteria.required_pass_probability;
  std::uint64_t passes = 0;
  std::array<std::uint64_t, kCategories> criterion_passes{};
  std::array<std::vector<double>, kCategories> shares;
  for (auto& v : shares) v.reserve(a.tallies.size());
  for (const auto& t : a.tallies) {
    const Judgement j = judge(t, criteria);
    passes += j.pass ? 1 : 0;
    for (int c = 0; c < kCategories; ++c) {
      criterion_passes[c] += j.passes[c] ? 1 : 0;
      shares[c].push_back(j.shares[c]);
    }
    s.marks += t.marks;
    for (int f = 0; f < flight::kFates; ++f) s.fates[f] += t.fates[f];
  }
  s.passed = passes;
  s.pass = wilson(passes, s.replicates);
  s.passes = s.pass.estimate >= s.required;
  s.settled = s.pass.low >= s.required || s.pass.high < s.required;
  for (int c = 0; c < kCategories; ++c) {
    auto& v = shares[c];
    CriterionSummary& cs = s.criteria[c];
    cs.name = category_name(c);
    cs.limit = category_limit(criteria, c);
    double sum = 0;
    for (double x : v) sum += x;  // in replicate order: deterministic
    cs.mean_share = v.empty() ? 0 : sum / static_cast<double>(v.size());
    std::sort(v.begin(), v.end());
    cs.q05 = quantile_sorted(v, 0.05);
    cs.q50 = quantile_sorted(v, 0.50);
    cs.q95 = quantile_sorted(v, 0.95);
    cs.pass = wilson(criterion_passes[c], s.replicates);
  }
  // The criterion least likely to pass; on a tie, the one whose mean share comes
  // closest to its limit.
  auto tighter = [&](int a, int b) {
    const auto &x = s.criteria[a], &y = s.criteria[b];
    if (x.pass.estimate != y.pass.estimate) return x.pass.estimate < y.pass.estimate;
    const double rx = x.limit > 0 ? x.mean_share / x.limit : x.mean_share, ry = y.limit > 0 ? y.mean_share / y.limit : y.mean_share;
    return rx > ry;
  };
  s.deciding = 0;
  for (int c = 1; c < kCategories; ++c)
    if (tighter(c, s.deciding)) s.deciding = c;
  s.marks_per_nail = s.nails ? static_cast<double>(s.marks) / static_cast<double>(s.nails) : 0;
  s.queries_per_nail = s.nails ? static_cast<double>(a.queries) / static_cast<double>(s.nails) : 0;
  return s;
}

}  // namespace j232::assess
