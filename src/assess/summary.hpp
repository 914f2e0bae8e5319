#pragma once
// What a run means: P(pass) with its interval, each criterion's share distribution and
// pass probability, the verdict and the criterion that decides it (docs/model.md §5.6).
#include <array>
#include <string>
#include <vector>

#include "assess/exact_pass.hpp"
#include "assess/runner.hpp"

namespace j232::assess {

struct CriterionSummary {
  std::string name;
  double limit = 0;
  double mean_share = 0, q05 = 0, q50 = 0, q95 = 0;
  Interval pass;
};

// Whether the simulated test really happened. A run that is not valid gets no verdict:
// no nail struck, too many nails cut off by the run's limits (their end is unknown), or
// any non-finite number.
inline constexpr double kMaxCutOffShare = 0.01;    // of the nails struck
inline constexpr double kWarnCutOffShare = 0.0025;  // a quarter of it: warned about, naming the limits
inline constexpr double kUnusualTipSpeed = 100.0;   // m/s: above it a blade is unusual (said, not refused)
// The thrown speed over the tip speed that published measurements report (result.json
// names the source); a mean outside it is flagged.
inline constexpr std::array<double, 2> kPublishedThrownOverTip{0.8, 1.4};
struct Validity {
  bool valid = true;
  std::vector<std::string> reasons;  // one sentence each, for the terminal, report and result.json
};

// The P(pass) a verdict rests on (run.estimator): the share of replicates that passed, or
// the exact sum over every nail's outcome (assess/exact_pass.hpp), whichever has the
// narrower interval by default.
enum class Basis { Replicates, EveryNail };
const char* basis_name(Basis b);  // "replicates", "every_nail"

struct VerdictEstimate {
  Basis basis = Basis::Replicates;
  Interval pass;          // the basis's estimate and 95 % interval
  Interval replicates;    // the replicates' share (Wilson)
  ExactPass exact;        // the exact estimate (its interval with draws > 0)
  std::string why_basis;  // one clause: why this basis
};

// The verdict's estimate for the run so far, with `exact_draws` bootstrap draws for the
// exact one's interval (0: the exact value alone, and the replicates decide). Also the
// stop rules' test between batches.
VerdictEstimate verdict_estimate(const Assessment& a, const scenario::Scenario& scenario, int exact_draws);

struct Summary {
  std::uint64_t replicates = 0, passed = 0, nails = 0, struck = 0, marks = 0, uncounted_marks = 0;
  Interval pass;  // the share of replicates that passed (Wilson)
  double required = 0;
  // The verdict: P(pass) on its basis (verdict.pass) against the required probability.
  VerdictEstimate verdict;
  int looks = 0;           // a stop rule's looks at it, and what stopped the batches (Assessment's)
  std::string stopped_by;
  bool passes = false;
  bool settled = false;  // the verdict's 95 % interval lies wholly on one side of `required`
  std::array<CriterionSummary, kCategories> criteria;
  int deciding = 0;  // the criterion least likely to pass
  double marks_per_nail = 0;
  std::array<std::uint64_t, flight::kFates> fates{};
  double queries_per_nail = 0;
  double exit_speed_mean = 0;  // m/s, off the first strike
  Validity validity;
  // What a reader should know before trusting the numbers, one sentence each: a cut-off
  // share nearing its limit (naming the limits that cut nails off), a mean thrown speed
  // outside the published band, an unusual tip speed.
  std::vector<std::string> warnings;
  std::array<std::uint64_t, flight::kCutOffReasons> cut_off_by{};
  // P(pass) computed exactly from every nail's outcome (assess/exact_pass.hpp): the value,
  // and with exact_draws > 0 its 95 % interval (also in `verdict`).
  ExactPass exact;
};

// Judges the run against the scenario's criteria and checks that the test really happened.
// `exact_draws`: bootstrap draws for the exact estimate's interval (0: its value alone).
Summary summarise(const Assessment& a, const scenario::Scenario& scenario, int exact_draws = 0);

}  // namespace j232::assess
