#include "assess/runner.hpp"

#include <chrono>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

namespace j232::assess {

namespace {

constexpr std::uint64_t kChunk = 8;  // replicates per chunk: fixed, so the merge order is too

// A chunk's results have the same shape as the whole assessment's; merged in order.
void merge(Assessment& into, const Assessment& c) {
  into.tallies.insert(into.tallies.end(), c.tallies.begin(), c.tallies.end());
  into.marks.insert(into.marks.end(), c.marks.begin(), c.marks.end());
  into.exit_speed.merge(c.exit_speed);
  into.mark_energy.merge(c.mark_energy);
  into.board_energy.merge(c.board_energy);
  into.board_energy_per_width.merge(c.board_energy_per_width);
  into.contact_radius.merge(c.contact_radius);
  into.nails += c.nails;
  into.struck += c.struck;
  into.queries += c.queries;
  into.unlocated_marks += c.unlocated_marks;
}

void run_chunk(const Simulator& sim, std::uint64_t first, std::uint64_t count, Assessment& c) {
  const int nails = sim.scenario().feed.nails;
  c.tallies.resize(count);
  c.marks.reserve(count * static_cast<std::uint64_t>(nails) / 2);
  for (std::uint64_t r = 0; r < count; ++r) {
    const std::uint64_t replicate = first + r;
    ReplicateTally& tally = c.tallies[r];
    for (int n = 0; n < nails; ++n) {
      const NailOutcome o = sim.simulate(replicate, n);
      tally.add(o.flight);
      ++c.nails;
      c.queries += static_cast<std::uint64_t>(o.flight.queries);
      if (o.flight.fate == flight::Fate::NotStruck) continue;
      ++c.struck;
      c.exit_speed.add(o.exit_speed);
      c.contact_radius.add(o.contact_radius);
      if (o.flight.board_energy >= 0) {
        c.board_energy.add(o.flight.board_energy);
        c.board_energy_per_width.add(o.flight.board_energy_per_width);
      }
      const int located = std::min(o.flight.mark_count, flight::FlightResult::kMaxMarks);
      c.unlocated_marks += static_cast<std::uint64_t>(o.flight.mark_count - located);
      for (int m = 0; m < located; ++m) {
        c.marks.push_back({static_cast<std::uint32_t>(replicate), static_cast<std::uint32_t>(n), o.flight.marks[m]});
        c.mark_energy.add(o.flight.marks[m].normal_energy);
      }
    }
  }
}

}  // namespace

void run_replicates(const Simulator& sim, std::uint64_t first, std::uint64_t count, Assessment& into,
                    Progress* progress) {
  const std::uint64_t chunks = (count + kChunk - 1) / kChunk;
  std::vector<Assessment> results(chunks);
  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, chunks, 1), [&](const tbb::blocked_range<std::uint64_t>& range) {
    for (std::uint64_t c = range.begin(); c != range.end(); ++c) {
      const std::uint64_t start = first + c * kChunk;
      const std::uint64_t n = std::min(kChunk, first + count - start);
      run_chunk(sim, start, n, results[c]);
      if (progress) progress->done += static_cast<long long>(n);
    }
  });
  for (const auto& c : results) merge(into, c);  // in chunk order: deterministic
}

Assessment run_assessment(const Simulator& sim, int threads, Progress* progress) {
  const auto& run = sim.scenario().run;
  const int available = static_cast<int>(tbb::this_task_arena::max_concurrency());
  const int used = threads > 0 ? threads : available;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(used));
  Assessment a;
  a.threads = used;
  const auto start = std::chrono::steady_clock::now();
  const auto first_batch = static_cast<std::uint64_t>(run.replicates);
  if (progress) progress->total = run.target_half_width ? run.max_replicates : run.replicates;
  run_replicates(sim, 0, first_batch, a, progress);
  if (run.target_half_width) {
    // Batches of the first batch's size until the interval is narrow enough.
    for (;;) {
      std::uint64_t passes = 0;
      for (const auto& t : a.tallies) passes += judge(t, sim.scenario().criteria).pass ? 1 : 0;
      const Interval i = wilson(passes, a.tallies.size());
      const auto done = static_cast<std::uint64_t>(a.tallies.size());
      if (0.5 * (i.high - i.low) <= *run.target_half_width || done >= static_cast<std::uint64_t>(run.max_replicates)) break;
      run_replicates(sim, done, std::min(first_batch, static_cast<std::uint64_t>(run.max_replicates) - done), a, progress);
    }
  }
  a.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return a;
}

}  // namespace j232::assess
