#include "assess/summary.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "flight/face_touch.hpp"

namespace j232::assess {

namespace {

// "12 by [run] time_limit (3 s), 2 by the contact search's step cap (4000)": the limits
// that cut the run's nails off, most first.
std::string cut_off_limits(const Assessment& a, const scenario::Scenario& s) {
  std::vector<std::pair<std::uint64_t, std::string>> parts;
  for (int k = 1; k < flight::kCutOffReasons; ++k) {
    const auto n = k < static_cast<int>(a.cut_off_by.counts.size()) ? a.cut_off_by.counts[static_cast<std::size_t>(k)] : 0;
    if (n == 0) continue;
    std::string what;
    switch (static_cast<flight::CutOff>(k)) {
      case flight::CutOff::TimeLimit: what = fmt::format("[run] time_limit ({:g} s)", s.time_limit()); break;
      case flight::CutOff::MaxBounces: what = fmt::format("[run] max_bounces ({})", s.max_bounces()); break;
      case flight::CutOff::FlightSteps: what = fmt::format("the flight's step cap ({} chords)", flight::kMaxFlightSteps); break;
      case flight::CutOff::MaxStrikes: what = fmt::format("[run] max_strikes ({} blade strikes)", s.max_strikes()); break;
      case flight::CutOff::SearchSteps:
        what = fmt::format("the contact searches' limits ({} steps against a blade, {} against the scene's faces, or more faces "
                           "within a nanosecond of flight than a search keeps)",
                           strike::kMaxSearchSteps, flight::kMaxFaceSearchSteps);
        break;
      case flight::CutOff::ContactsInPass:
        what = fmt::format("[run] max_contacts_per_pass ({} contacts in one pass)", s.run.max_contacts_per_pass);
        break;
      case flight::CutOff::UnresolvedContact: what = "a blade touch the impulse could not resolve"; break;
      case flight::CutOff::NonFinite: what = "a non-finite state"; break;
      case flight::CutOff::Wedged:
        what = "a wedge (64 contacts with two bodies in turn, each within 10 ns of the one before: pinched between a knife and a "
               "fixed face, in a corner, or 6 strikes in turn by two knives; contacts resolved one at a time cannot free it)";
        break;
      case flight::CutOff::MaxGentleContacts:
        what = fmt::format("[run] max_gentle_contacts ({} contacts slower than sqrt(2 g D))", s.run.max_gentle_contacts);
        break;
      case flight::CutOff::SankIntoFace:
        what = fmt::format("a sustained contact the face search cannot follow (pressed {:g} mm into a face as it slid or turned "
                           "on it)",
                           1e3 * flight::kDeepestSink);
        break;
      case flight::CutOff::None: break;
    }
    parts.emplace_back(n, std::move(what));
  }
  std::stable_sort(parts.begin(), parts.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::string out;
  for (const auto& [n, what] : parts) out += fmt::format("{}{} by {}", out.empty() ? "" : ", ", n, what);
  return out.empty() ? "by no recorded limit" : out;
}

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
        fmt::format("{} of {} struck nails ({:.1f} %) were cut off still moving ({}), more than the {:g} % allowed: "
                    "where they would have ended is unknown; raise the limits",
                    cut, a.struck, 100.0 * static_cast<double>(cut) / static_cast<double>(a.struck), cut_off_limits(a, s),
                    100 * kMaxCutOffShare));
  if (a.non_finite > 0)
    refuse(
        fmt::format("{} nails reached a non-finite state (infinite or not-a-number speed or position): the inputs "
                    "are outside what the model can handle",
                    a.non_finite));
  return v;
}

std::vector<std::string> warnings(const Assessment& a, const scenario::Scenario& s, const Validity& validity) {
  std::vector<std::string> w = s.notes;  // what the reader noticed in the file
  const std::uint64_t cut = a.fates[static_cast<std::size_t>(flight::Fate::CutOff)];
  const double share = a.struck ? static_cast<double>(cut) / static_cast<double>(a.struck) : 0.0;
  if (validity.valid && share >= kWarnCutOffShare)
    w.push_back(fmt::format("{} of {} struck nails ({:.2f} %) were cut off still moving ({}): nearing the {:g} % at which a run "
                            "is invalid; raising those limits would show where they end",
                            cut, a.struck, 100 * share, cut_off_limits(a, s), 100 * kMaxCutOffShare));
  const double tip = s.tip_speed();
  if (a.exit_speed.total > 0 && tip > 0) {
    const double ratio = a.exit_speed.mean() / tip;
    if (ratio < kPublishedThrownOverTip[0] || ratio > kPublishedThrownOverTip[1])
      w.push_back(fmt::format("the nails' mean speed off the blade is {:.2f} x the tip speed, outside the published band "
                              "{:g}-{:g}: check the blade's speed, edge and restitution inputs",
                              ratio, kPublishedThrownOverTip[0], kPublishedThrownOverTip[1]));
  }
  if (tip > kUnusualTipSpeed)
    w.push_back(fmt::format("the blade's tip speed, {:.0f} m/s, is unusual for a rotary mower (above {:g} m/s); the run "
                            "goes ahead as given",
                            tip, kUnusualTipSpeed));
  return w;
}

}  // namespace

const char* basis_name(Basis b) { return b == Basis::EveryNail ? "every_nail" : "replicates"; }

VerdictEstimate verdict_estimate(const Assessment& a, const scenario::Scenario& scenario, int exact_draws) {
  using Estimator = scenario::RunSpec::Estimator;
  VerdictEstimate v;
  v.replicates = wilson(a.passed, a.replicates);
  v.pass = v.replicates;
  const Estimator asked = scenario.run.estimator;
  if (asked == Estimator::Replicates) {
    v.why_basis = "run.estimator = \"replicates\"";
    return v;
  }
  v.exact = exact_pass(a.outcomes, scenario.feed.nails, scenario.criteria, scenario.run.seed, exact_draws);
  if (!v.exact.computed) {
    v.why_basis = "P(pass) from every nail was not computed: " + v.exact.not_computed;
    return v;
  }
  if (exact_draws <= 0) {
    v.why_basis = "P(pass) from every nail was computed without its interval";
    return v;
  }
  const Interval exact{v.exact.value, v.exact.low, v.exact.high};
  const bool narrower = exact.high - exact.low < v.replicates.high - v.replicates.low;
  if (asked == Estimator::EveryNail || narrower) {
    v.basis = Basis::EveryNail;
    v.pass = exact;
    v.why_basis = asked == Estimator::EveryNail ? "run.estimator = \"every_nail\"" : "its interval is the narrower";
  } else {
    v.why_basis = "its interval is the narrower";
  }
  return v;
}

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
  s.verdict = verdict_estimate(a, scenario, exact_draws);
  s.looks = a.looks;
  s.stopped_by = a.stopped_by;
  s.pass = s.verdict.replicates;
  // Shown beside the verdict's basis even when the replicates were asked to decide.
  s.exact = scenario.run.estimator == scenario::RunSpec::Estimator::Replicates
                ? exact_pass(a.outcomes, scenario.feed.nails, criteria, scenario.run.seed, exact_draws)
                : s.verdict.exact;
  s.passes = s.verdict.pass.estimate >= s.required;
  s.settled = s.verdict.pass.low >= s.required || s.verdict.pass.high < s.required;
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
  s.warnings = warnings(a, scenario, s.validity);
  for (int k = 0; k < flight::kCutOffReasons && k < static_cast<int>(a.cut_off_by.counts.size()); ++k)
    s.cut_off_by[static_cast<std::size_t>(k)] = a.cut_off_by.counts[static_cast<std::size_t>(k)];
  return s;
}

}  // namespace j232::assess
