#include "assess/summary.hpp"

#include <fmt/format.h>

namespace j232::assess {

namespace {

Validity check_validity(const Assessment& a, const scenario::Scenario& s) {
  Validity v;
  auto refuse = [&](std::string why) {
    v.valid = false;
    v.reasons.push_back(std::move(why));
  };
  if (a.replicates == 0) refuse("no replicate was run");
  if (a.struck == 0)
    refuse(
        fmt::format("the blade struck none of the {} nails fed, so no test happened: check that the feed stations lie "
                    "within their blade's tip circle and the blade's speed and height",
                    a.nails));
  const std::uint64_t cut = a.fates[static_cast<std::size_t>(flight::Fate::CutOff)];
  if (a.struck > 0 && static_cast<double>(cut) > kMaxCutOffShare * static_cast<double>(a.struck))
    refuse(
        fmt::format("{} of {} struck nails ({:.1f} %) were cut off still moving by [run] time_limit ({:g} s), "
                    "max_bounces ({}) or the step limit, more than the {:g} % allowed: where they would have ended "
                    "is unknown; raise the limits",
                    cut, a.struck, 100.0 * static_cast<double>(cut) / static_cast<double>(a.struck), s.run.time_limit, s.run.max_bounces,
                    100 * kMaxCutOffShare));
  if (a.non_finite > 0)
    refuse(
        fmt::format("{} nails reached a non-finite state (infinite or not-a-number speed or position): the inputs "
                    "are outside what the model can handle",
                    a.non_finite));
  return v;
}

}  // namespace

Summary summarise(const Assessment& a, const scenario::Scenario& scenario, int exact_draws) {
  const scenario::CriteriaSpec& criteria = scenario.criteria;
  Summary s;
  s.replicates = a.replicates;
  s.nails = a.nails;
  s.struck = a.struck;
  s.required = criteria.required_pass_probability;
  s.marks = a.marks;
  s.uncounted_marks = a.uncounted_marks;
  s.fates = a.fates;
  s.passed = a.passed;
  s.pass = wilson(a.passed, s.replicates);
  s.passes = s.pass.estimate >= s.required;
  s.settled = s.pass.low >= s.required || s.pass.high < s.required;
  for (int c = 0; c < kCategories; ++c) {
    const ShareDistribution& d = a.shares[c];
    CriterionSummary& cs = s.criteria[c];
    cs.name = category_name(c);
    cs.limit = category_limit(criteria, c);
    cs.mean_share = d.mean();
    cs.q05 = d.quantile(0.05);
    cs.q50 = d.quantile(0.50);
    cs.q95 = d.quantile(0.95);
    cs.pass = wilson(a.criterion_passed[c], s.replicates);
  }
  // The criterion least likely to pass; on a tie, the one whose mean share comes
  // closest to its limit.
  auto tighter = [&](int i, int j) {
    const auto &x = s.criteria[i], &y = s.criteria[j];
    if (x.pass.estimate != y.pass.estimate) return x.pass.estimate < y.pass.estimate;
    const double rx = x.limit > 0 ? x.mean_share / x.limit : x.mean_share, ry = y.limit > 0 ? y.mean_share / y.limit : y.mean_share;
    return rx > ry;
  };
  s.deciding = 0;
  for (int c = 1; c < kCategories; ++c)
    if (tighter(c, s.deciding)) s.deciding = c;
  s.marks_per_nail = s.nails ? static_cast<double>(s.marks) / static_cast<double>(s.nails) : 0;
  s.exit_speed_mean = a.exit_speed.mean();
  s.queries_per_nail = s.nails ? static_cast<double>(a.queries) / static_cast<double>(s.nails) : 0;
  s.validity = check_validity(a, scenario);
  s.exact = exact_pass(a.outcomes, scenario.feed.nails, criteria, scenario.run.seed, exact_draws);
  return s;
}

}  // namespace j232::assess
