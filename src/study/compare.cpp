#include "study/compare.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "assess/chunk_runner.hpp"
#include "assess/cluster.hpp"
#include "assess/paired_runs.hpp"
#include "assess/paired_sums.hpp"
#include "assess/summary.hpp"

namespace j232::study {

namespace {
constexpr double kZ = 1.959963984540054;

// A mean over units and its spread, from the sums of a paired comparison (the units added
// in their order: deterministic).
struct Moments {
  double n = 0, sum = 0, sum_sq = 0;
  double mean() const { return n > 0 ? sum / n : 0.0; }
  double variance() const { return n > 1 ? std::max(0.0, (sum_sq - sum * sum / n) / (n - 1)) : 0.0; }
  // Clipped to the values the quantity can take: [0, 1] for a share, [-1, 1] for a difference.
  // Rounding noise of a sum of shares (a difference of 1e-19 where every replicate gave
  // zero) is shown as the zero it is.
  MeanInterval interval(double lowest, double highest) const {
    const double half = n > 1 ? kZ * std::sqrt(variance() / n) : 0.0;
    const auto clean = [](double x) { return std::abs(x) < 1e-12 ? 0.0 : x; };
    return {clean(mean()), clean(std::max(lowest, mean() - half)), clean(std::min(highest, mean() + half))};
  }
};

// A design's figure j, and its difference from the first design's.
Moments own(const assess::PairedSums& p, std::size_t d, std::size_t j) {
  const std::size_t at = p.own(d, j);
  return {static_cast<double>(p.units), p.sum[at], p.squares[at]};
}
Moments versus_first(const assess::PairedSums& p, std::size_t d, std::size_t j) {
  const std::size_t at = p.versus_first(d, j);
  return {static_cast<double>(p.units), p.diff[at], p.diff_squares[at]};
}

// The figures of a J232 design, a row per replicate: the four shares, then the pass (0 or 1).
constexpr std::size_t kFigures = assess::kCategories + 1;
constexpr std::size_t kPass = assess::kCategories;

// Every design's rows (`designs` of them, each `rows(d)`), replicate by replicate, in
// replicate order (one block: a comparison's replicates are few); a replicate's figure
// differs where its value does.
template <class Rows>
assess::PairedSums paired_sums(std::size_t designs, Rows&& rows) {
  const std::uint64_t units = rows(0).size();
  assess::PairedSums p(designs, kFigures);
  p.add_units(
      0, units, std::max<std::uint64_t>(units, 1),
      [&](std::uint64_t r, double* y) {
        for (std::size_t d = 0; d < designs; ++d)
          for (std::size_t j = 0; j < kFigures; ++j) y[d * kFigures + j] = rows(d)[r][j];
      },
      [&](std::uint64_t r, std::size_t d, std::size_t j) { return rows(d)[r][j] != rows(0)[r][j]; });
  return p;
}
}  // namespace

assess::ReplicateSink DesignRecorder::sink() {
  return [this](std::uint64_t r, const assess::Judgement& j) {
    auto& row = record.per_replicate.at(r);
    for (int k = 0; k < assess::kCategories; ++k) row[static_cast<std::size_t>(k)] = j.shares[static_cast<std::size_t>(k)];
    row[assess::kCategories] = j.pass ? 1.0 : 0.0;
  };
}

DesignRecord DesignRecorder::finish(const scenario::Scenario& s, const assess::Assessment& a, const assess::Summary* summary) && {
  DesignResult& res = record.result;
  res.file = s.file;
  res.title = s.title;
  res.pass = assess::wilson(a.passed, a.replicates);
  const assess::Summary sum = summary ? *summary : assess::summarise(a, s, assess::kExactDraws);
  res.verdict = !sum.validity.valid ? "invalid" : sum.passes ? "passes" : "fails";
  res.invalid_because = sum.validity.reasons;
  res.settled = sum.validity.valid && sum.settled;
  res.required = sum.required;
  res.exact = sum.exact;
  res.basis = assess::basis_name(sum.verdict.basis);
  res.deciding = sum.deciding;
  res.deciding_pass = sum.criteria[static_cast<std::size_t>(sum.deciding)].pass.estimate;
  {
    const assess::PairedSums own_sums = paired_sums(1, [&](std::size_t) -> const auto& { return record.per_replicate; });
    for (std::size_t k = 0; k < assess::kCategories; ++k) res.shares[k] = own(own_sums, 0, k).interval(0.0, 1.0);
  }
  res.limits = {s.criteria.hits_zone, s.criteria.punctures_zone, s.criteria.hits_outside, s.criteria.punctures_outside};
  res.marks = a.marks;
  res.nails = a.nails;
  // Mean and standard error from a histogram's bin midpoints (0.5 m/s bins for the speed,
  // whole strikes for the strikes: the spread is that of the nails, not of the binning).
  const auto mean_error = [](const assess::Histogram& h, double scale) {
    MeanError out;
    if (h.total < 2) return out;
    double sum1 = 0, sum2 = 0;  // of the binned values (a shift within the bins cancels)
    for (std::size_t k = 0; k < h.counts.size(); ++k) {
      const double mid = h.origin + (static_cast<double>(k) + 0.5) * h.bin_width, c = static_cast<double>(h.counts[k]);
      sum1 += c * mid, sum2 += c * mid * mid;
    }
    const double n = static_cast<double>(h.total), binned = sum1 / n;
    const double variance = std::max(0.0, (sum2 / n - binned * binned) * n / (n - 1));
    out.mean = h.mean() * scale;  // exact
    out.standard_error = std::sqrt(variance / n) * scale;
    return out;
  };
  res.exit_speed_over_tip = mean_error(a.exit_speed, s.tip_speed() > 0 ? 1.0 / s.tip_speed() : 0.0);
  res.strikes_per_struck_nail = mean_error(a.strikes, 1.0);
  return std::move(record);
}

namespace {
// The comparison from every design's result and the paired sums of their replicates.
// (`replicates`: the run's; in an MPI job only rank 0's sums hold them.)
Comparison compared(const std::vector<DesignRecord>& designs, const assess::PairedSums& p, unsigned long long seed, std::uint64_t replicates) {
  J232_CHECK(p.units == replicates || !assess::cluster::is_writer());
  Comparison c;
  c.seed = seed;
  c.replicates = replicates;
  for (const auto& d : designs) c.designs.push_back(d.result);
  const double n = static_cast<double>(c.replicates);
  for (std::size_t d = 1; d < designs.size(); ++d) {
    Difference diff;
    diff.replicates_differing = p.units_differing[d - 1];
    if (diff.replicates_differing == 0 && c.replicates > 0)
      diff.differing_at_most = 1.0 - std::pow(0.025, 1.0 / static_cast<double>(c.replicates));
    for (std::size_t k = 0; k < kFigures; ++k) {
      const double independent = n > 1 ? kZ * std::sqrt((own(p, 0, k).variance() + own(p, d, k).variance()) / n) : 0.0;
      if (k == kPass) {
        // The pass indicators' difference: Newcombe's paired interval, which does not
        // collapse to zero width when few or no replicates differ. Its table from the sums of
        // 0/1 values (exact in double): replicates that differ number only_first + only_other,
        // and the differences add up to only_other - only_first.
        const std::uint64_t differ = p.differing[p.versus_first(d, k)];
        const auto gained = static_cast<std::int64_t>(p.diff[p.versus_first(d, k)]);
        const auto only_other = static_cast<std::uint64_t>((static_cast<std::int64_t>(differ) + gained) / 2);
        const std::uint64_t only_first = differ - only_other;
        const auto first_passed = static_cast<std::uint64_t>(p.sum[p.own(0, k)]);
        // (Pass values are exactly 0 or 1, the sink's: then the counts are whole and fit.)
        J232_CHECK((static_cast<std::int64_t>(differ) + gained) % 2 == 0 && static_cast<std::int64_t>(differ) + gained >= 0);
        J232_CHECK(first_passed >= only_first && first_passed - only_first + differ <= c.replicates);
        const std::uint64_t both = first_passed - only_first, neither = c.replicates - both - only_first - only_other;
        const assess::Interval nc = assess::newcombe_paired(both, only_first, only_other, neither);
        diff.pass = {nc.estimate, nc.low, nc.high};
        diff.independent_pass_half_width = independent;
      } else {
        diff.shares[k] = versus_first(p, d, k).interval(-1.0, 1.0);
        diff.independent_half_width[k] = independent;
      }
    }
    c.versus_first.push_back(diff);
  }
  return c;
}
}  // namespace

Comparison compare_records(const std::vector<DesignRecord>& designs, unsigned long long seed) {
  if (designs.size() < 2) throw std::invalid_argument("a comparison needs at least two designs");
  for (const auto& d : designs)
    if (d.per_replicate.size() != designs.front().per_replicate.size())
      throw std::invalid_argument("designs compared must have run the same replicates");
  return compared(designs, paired_sums(designs.size(), [&](std::size_t d) -> const auto& { return designs[d].per_replicate; }), seed,
                  designs.front().per_replicate.size());
}

Comparison compare_designs(std::vector<scenario::Scenario> designs, int threads, assess::Progress* progress,
                           const std::function<void(std::size_t, const scenario::Scenario&)>& on_design) {
  if (designs.size() < 2) throw std::invalid_argument("a comparison needs at least two designs");
  const unsigned long long seed = designs.front().run.seed;
  const auto replicates = static_cast<std::uint64_t>(designs.front().run.replicates);
  for (auto& s : designs) {
    s.run.seed = seed;
    s.run.replicates = static_cast<long long>(replicates);
    s.run.target_half_width.reset();
    s.run.until_settled = false;  // every design runs the same replicates, no stop rule
  }
  // The one paired comparison (assess::run_paired): each design's replicates run in turn as
  // j232 run runs them, each replicate's four shares and pass handed over in replicate order
  // (and kept, for each design's own result); a comparison's replicates are few, so one
  // segment and one block.
  const std::size_t nd = designs.size();
  std::vector<assess::Assessment> runs(nd);
  std::vector<DesignRecorder> recorders;
  for (std::size_t d = 0; d < nd; ++d) recorders.emplace_back(replicates);
  assess::PairedRuns paired;
  paired.designs = nd, paired.figures = kFigures, paired.units = replicates;
  paired.block = paired.segment = std::max<std::uint64_t>(replicates, 1);
  paired.run = [&](std::size_t d, std::uint64_t first, std::uint64_t count, const assess::UnitSink& sink) {
    J232_CHECK(first == 0 && count == replicates);  // (one segment: each design runs once, whole)
    if (on_design) on_design(d, designs[d]);
    const assess::Simulator sim(designs[d]);
    if (progress) progress->total = static_cast<long long>(count), progress->done = 0;
    const assess::ReplicateSink keep = recorders[d].sink();
    assess::on_threads(threads, [&] {
      assess::run_replicates(sim, first, count, runs[d], progress, {}, [&](std::uint64_t r, const assess::Judgement& j) {
        keep(r, j);
        sink(r, recorders[d].record.per_replicate[r].data());
      });
    });
  };
  const assess::PairedSums sums = assess::run_paired(paired);
  std::vector<DesignRecord> records;
  for (std::size_t d = 0; d < nd; ++d) records.push_back(std::move(recorders[d]).finish(designs[d], runs[d]));
  return compared(records, sums, seed, replicates);
}

}  // namespace j232::study
