#pragma once
// Comparing designs (docs/model.md §6a): the same test run on several scenarios with
// common random numbers - the same seed, so replicate r of every design drops its nails
// from the same random feed and draws the same random flights - and each design's
// difference from the first judged replicate by replicate. Paired, the difference's
// interval is far tighter than two independent runs would give.
#include <array>
#include <string>
#include <vector>

#include "assess/exact_pass.hpp"
#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "assess/statistics.hpp"
#include "scenario/scenario.hpp"

namespace j232::study {

// A mean over replicates with its 95 % interval (normal approximation, mean +/- 1.96 s/sqrt(n)).
struct MeanInterval {
  double mean = 0, low = 0, high = 0;
};

struct MeanError {
  double mean = 0, standard_error = 0;
};
struct DesignResult {
  std::string file, title;
  // Its own verdict, as `j232 run` would give it: "passes", "fails" or "invalid" (no
  // verdict: invalid_because says why), whether its interval settles it, P(pass) from
  // every nail, and the criterion that decides it with that criterion's mean share.
  std::string verdict = "invalid";
  std::vector<std::string> invalid_because;
  bool settled = false;
  double required = 0.9;
  assess::ExactPass exact;
  std::string basis = "replicates";  // the P(pass) its verdict rests on (assess::basis_name)
  int deciding = 0;
  double deciding_pass = 0;  // P(the deciding criterion passes)
  assess::Interval pass;  // P(pass), Wilson
  std::array<MeanInterval, assess::kCategories> shares;
  std::array<double, assess::kCategories> limits{};
  std::uint64_t marks = 0, nails = 0;
  // Per-nail means with their standard errors (nails are independent: the errors of two
  // designs' means add in quadrature, a conservative interval for their difference): the
  // thrown speed over the tip speed, and blade strikes per struck nail.
  MeanError exit_speed_over_tip, strikes_per_struck_nail;
};

// A design minus the first, replicate by replicate.
struct Difference {
  MeanInterval pass;  // difference of the pass indicators: of P(pass)
  std::array<MeanInterval, assess::kCategories> shares;
  // The half-width two independent runs of the same size would give (from the designs'
  // own spreads), to show what the pairing gained.
  std::array<double, assess::kCategories> independent_half_width{};
  double independent_pass_half_width = 0;
  // Replicates in which a share or the verdict differs. When none does, the paired
  // intervals are zero-wide: they say what this run saw, and `differing_at_most` bounds
  // what it could have missed, the share of replicates that could differ (95 %, exact
  // binomial: 1 - 0.025^(1/R), about 3.7 / R); P(pass) can differ by no more than that.
  std::uint64_t replicates_differing = 0;
  double differing_at_most = 0;
};

struct Comparison {
  std::uint64_t replicates = 0;
  unsigned long long seed = 0;
  std::vector<DesignResult> designs;
  std::vector<Difference> versus_first;  // one per design after the first
};

// One design's run as a comparison needs it: its result and, per replicate, the four shares
// and the pass (5 numbers per replicate).
struct DesignRecord {
  DesignResult result;
  std::vector<std::array<double, assess::kCategories + 1>> per_replicate;
};
// Collects the per-replicate numbers of a run (its replicate sink), then its result.
struct DesignRecorder {
  DesignRecord record;
  explicit DesignRecorder(std::uint64_t replicates) { record.per_replicate.resize(replicates); }
  assess::ReplicateSink sink();
  // (`summary`: the run's own, when it has one; else it is worked out here.)
  DesignRecord finish(const scenario::Scenario& s, const assess::Assessment& a, const assess::Summary* summary = nullptr) &&;
};
// The comparison of designs run with the same seed and replicates (each design minus the first).
Comparison compare_records(const std::vector<DesignRecord>& designs, unsigned long long seed);

// Runs every design with the first design's seed and replicates (each design's scenario
// is changed to them; a stop rule is not used). `on_design` is told before each run.
Comparison compare_designs(std::vector<scenario::Scenario> designs, int threads, assess::Progress* progress = nullptr,
                           const std::function<void(std::size_t, const scenario::Scenario&)>& on_design = {});

}  // namespace j232::study
