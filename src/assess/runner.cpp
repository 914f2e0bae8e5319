#include "assess/runner.hpp"

#include "assess/chunk.hpp"
#include "assess/chunk_runner.hpp"
#include "assess/cluster.hpp"
#include "assess/summary.hpp"
#include "invariant/check.hpp"

#include "units/quantity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <type_traits>

namespace j232::assess {

void ShareDistribution::add(double share) {
  ++counts[share];
  ++total;
  sum += share;
}

double ShareDistribution::quantile(double p) const {
  if (total == 0) return 0.0;
  // The values at sorted positions lo and lo + 1, found by walking the counts.
  const double h = static_cast<double>(total - 1) * p;
  const auto lo = static_cast<std::uint64_t>(std::floor(h));
  const std::uint64_t hi = std::min(lo + 1, total - 1);
  double at_lo = 0, at_hi = 0;
  std::uint64_t seen = 0;
  bool have_lo = false;
  for (const auto& [value, n] : counts) {
    seen += n;
    if (!have_lo && lo < seen) at_lo = value, have_lo = true;
    if (hi < seen) {
      at_hi = value;
      break;
    }
  }
  return at_lo + (h - static_cast<double>(lo)) * (at_hi - at_lo);
}

void ExitTable::add(const flight::FlightResult& f) {
  const flight::NailTrace& t = f.trace;
  const std::uint32_t key = exit_key(t.exit, t.exit_index);
  ++nails[key];
  const int counted = f.mark_count - f.uncounted_marks;
  if (counted <= 0) return;
  const auto c = static_cast<std::uint64_t>(counted);
  const int band = std::clamp(static_cast<int>(std::floor((t.exit_azimuth + units::pi) / (units::two_pi / kBands))), 0, kBands - 1);
  auto& row = marks[key];  // value-initialised to zeros when new
  row[static_cast<std::size_t>(band)] += c;
  marks_by_strikes[static_cast<std::size_t>(std::clamp(f.strikes, 1, 5) - 1)] += c;
  marks_by_first_touch[t.touch_count > 0 ? static_cast<std::size_t>(t.touches[0]) : flight::kTouchKinds] += c;
}

void ExitTable::merge(const ExitTable& o) {
  for (const auto& [k, n] : o.nails) nails[k] += n;
  for (const auto& [k, row] : o.marks) {
    auto& into = marks[k];
    for (int b = 0; b < kBands; ++b) into[static_cast<std::size_t>(b)] += row[static_cast<std::size_t>(b)];
  }
  for (std::size_t i = 0; i < marks_by_strikes.size(); ++i) marks_by_strikes[i] += o.marks_by_strikes[i];
  for (std::size_t i = 0; i < marks_by_first_touch.size(); ++i) marks_by_first_touch[i] += o.marks_by_first_touch[i];
}

void NailRecords::merge(const NailRecords& c) {
  zip(*this, c, [](auto& mine, const auto& theirs) {
    if constexpr (std::is_same_v<std::decay_t<decltype(mine)>, std::uint64_t>)
      mine += theirs;
    else
      mine.merge(theirs);
  });
}

namespace {

constexpr std::uint64_t kChunk = 8;   // replicates per chunk: fixed, so the merge order is too
constexpr std::uint64_t kWave = 128;  // chunks in flight at once: bounds memory, keeps both cores busy

void run_chunk(const Simulator& sim, std::uint64_t first, std::uint64_t count, ChunkResult& c) {
  const int nails = sim.scenario().feed.nails;
  c.tallies.resize(count);
  for (std::uint64_t r = 0; r < count; ++r) {
    const std::uint64_t replicate = first + r;
    ReplicateTally& tally = c.tallies[r];
    for (int n = 0; n < nails; ++n) {
      const NailOutcome o = sim.simulate(replicate, n);
      tally.add(o.flight);
      c.outcomes.add(o.station, marks_key(o.flight));
      ++c.nails;
      c.queries += static_cast<std::uint64_t>(o.flight.queries);
      if (o.flight.non_finite) ++c.non_finite;
      if (o.flight.fate == flight::Fate::NotStruck) continue;
      ++c.struck;
      c.bounces += static_cast<std::uint64_t>(o.flight.bounces), c.gentle_contacts += static_cast<std::uint64_t>(o.flight.gentle_contacts);
      c.wall_contacts += static_cast<std::uint64_t>(o.flight.wall_contacts);
      if (o.flight.fate == flight::Fate::CutOff) c.cut_off_by.add(static_cast<double>(o.flight.cut_off));
      if (o.flight.non_finite) continue;  // nothing of it is a number worth recording
      c.exit_speed.add(o.exit_speed);
      c.launch_elevation.add(o.launch_elevation / units::degree);
      for (std::size_t k = 0; k < o.flight.passes_by_contacts.size(); ++k)
        for (int p = 0; p < o.flight.passes_by_contacts[k]; ++p) c.contacts_per_pass.add(static_cast<double>(k + 1));
      c.most_contacts_in_pass.add(static_cast<std::uint64_t>(o.flight.most_contacts_in_pass));
      c.contact_radius.add(o.contact_radius);
      c.strikes.add(o.flight.strikes);
      c.most_strikes.add(static_cast<std::uint64_t>(o.flight.strikes));
      c.exits.add(o.flight);
      if (o.flight.board_energy >= 0) {
        c.board_energy.add(o.flight.board_energy);
        c.board_energy_per_width.add(o.flight.board_energy_per_width);
      }
      const int located = std::min(o.flight.mark_count, flight::FlightResult::kMaxMarks);
      c.unlocated_marks += static_cast<std::uint64_t>(o.flight.mark_count - located);
      for (int m = 0; m < located; ++m) {
        c.marks.push_back({static_cast<std::uint32_t>(replicate), static_cast<std::uint32_t>(n), o.flight.marks[m],
                           static_cast<std::uint16_t>(o.spindle), static_cast<std::uint16_t>(o.station), o.flight.strikes,
                           o.flight.flight_time, o.flight.trace});
        c.mark_energy.add(o.flight.marks[m].normal_energy);
      }
    }
  }
}

// Chunks are merged in index order: the replicates' judgements, then their marks.
void merge(Assessment& into, const ChunkResult& c, const scenario::CriteriaSpec& criteria, const MarkSink& sink,
           const ReplicateSink& replicate_sink) {
  std::size_t next_mark = 0;
  for (const ReplicateTally& t : c.tallies) {
    const std::uint64_t replicate = into.replicates++;
    const Judgement j = judge(t, criteria);
    if (replicate_sink) replicate_sink(replicate, j);
    into.passed += j.pass ? 1 : 0;
    for (int k = 0; k < kCategories; ++k) {
      into.criterion_passed[k] += j.passes[k] ? 1 : 0;
      into.shares[k].add(j.shares[k]);
    }
    into.marks += t.marks;
    into.uncounted_marks += t.uncounted_marks;
    for (int f = 0; f < flight::kFates; ++f) into.fates[f] += t.fates[f];
    // This replicate's located marks, in nail order.
    const std::size_t begin = next_mark;
    while (next_mark < c.marks.size() && c.marks[next_mark].replicate == replicate) ++next_mark;
    if (sink)
      for (std::size_t m = begin; m < next_mark; ++m) sink(c.marks[m]);
    const std::size_t n = next_mark - begin;
    if (!into.mark_sample_closed && (replicate == 0 || into.mark_sample.size() + n <= kMarkSample)) {
      into.mark_sample.insert(into.mark_sample.end(), c.marks.begin() + static_cast<std::ptrdiff_t>(begin),
                              c.marks.begin() + static_cast<std::ptrdiff_t>(next_mark));
      into.mark_sample_replicates = replicate + 1;
    } else {
      into.mark_sample_closed = true;
    }
  }
  J232_CHECK(next_mark == c.marks.size());  // every mark of the chunk is in one of its replicates, in order
  into.NailRecords::merge(c);
}

}  // namespace

void run_replicates(const Simulator& sim, std::uint64_t first, std::uint64_t count, Assessment& into, Progress* progress,
                    const MarkSink& sink, const ReplicateSink& replicate_sink) {
  const auto& criteria = sim.scenario().criteria;
  std::vector<ChunkResult> slots;
  ChunkWork work;
  work.chunks = (count + kChunk - 1) / kChunk;
  work.most_slots = kWave;
  const auto start = [&](std::uint64_t chunk) { return first + chunk * kChunk; };
  work.items = [&](std::uint64_t chunk) { return std::min(kChunk, first + count - start(chunk)); };
  work.run = [&](std::uint64_t chunk, std::size_t slot) {
    slots[slot].clear();
    run_chunk(sim, start(chunk), work.items(chunk), slots[slot]);
  };
  work.merge = [&](std::uint64_t, std::size_t slot) { merge(into, slots[slot], criteria, sink, replicate_sink); };
  work.pack = [&](std::size_t n) { return pack_chunks(slots, n); };
  work.unpack = [&](const std::string& bytes, std::size_t n) { unpack_chunks(bytes, slots, n); };
  work.progress = progress;
  slots.resize(static_cast<std::size_t>(wave_size(work)));
  run_chunks(work);
  if (cluster::size() > 1) {
    // Every rank continues from the merged result (the same path through whatever follows).
    std::string merged = cluster::rank() == 0 ? pack_assessment(into) : std::string();
    cluster::broadcast_from_writer(merged);
    if (cluster::rank() != 0) unpack_assessment(merged, into);
  }
  for (const auto& [key, n] : into.exits.nails)
    if (!into.exit_names.count(key)) into.exit_names[key] = sim.exit_name(exit_of(key), exit_index(key));
  for (const MarkRow& m : into.mark_sample)  // where the sampled marks' nails first left, too
    if (const auto key = exit_key(m.trace.first_exit, m.trace.first_exit_index); !into.exit_names.count(key))
      into.exit_names[key] = sim.exit_name(m.trace.first_exit, m.trace.first_exit_index);
}

Assessment run_assessment(const Simulator& sim, int threads, Progress* progress, const MarkSink& sink,
                          const ReplicateSink& replicate_sink) {
  const auto& run = sim.scenario().run;
  Assessment a;
  const auto start = std::chrono::steady_clock::now();
  const auto first_batch = static_cast<std::uint64_t>(run.replicates);
  const bool stop_rule = run.target_half_width || run.until_settled;
  const auto most = static_cast<std::uint64_t>(std::max(run.max_replicates, run.replicates));
  if (progress) progress->total = static_cast<long long>(first_batch);
  a.threads = on_threads(threads, [&] {
    run_replicates(sim, 0, first_batch, a, progress, sink, replicate_sink);
    if (!stop_rule) return;
    // Looks at the verdict's estimate (the interval the report will show: the same draws)
    // after batches that grow by half the replicates so far, so that the looks stay few
    // (their number grows as the logarithm of the replicates) and each costs little beside
    // the batch before it.
    const double required = sim.scenario().criteria.required_pass_probability;
    for (;;) {
      ++a.looks;
      const Interval i = verdict_estimate(a, sim.scenario(), kExactDraws).pass;
      if (run.target_half_width && 0.5 * (i.high - i.low) <= *run.target_half_width) {
        a.stopped_by = "target_half_width";
        break;
      }
      if (run.until_settled && (i.low >= required || i.high < required)) {
        a.stopped_by = "settled";
        break;
      }
      if (a.replicates >= most) {
        a.stopped_by = "max_replicates";
        break;
      }
      const std::uint64_t batch = std::min(std::max(first_batch, a.replicates / 2), most - a.replicates);
      if (progress) progress->looks = a.looks, progress->total = static_cast<long long>(a.replicates + batch);
      run_replicates(sim, a.replicates, batch, a, progress, sink, replicate_sink);
    }
  });
  a.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return a;
}

}  // namespace j232::assess
