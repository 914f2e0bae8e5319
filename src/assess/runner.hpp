#pragma once
// Replicates of the whole test, in parallel on oneTBB (DESIGN.md §4.6). Work is cut
// into fixed chunks of replicates; each chunk fills its own tallies; chunks are merged
// in index order. Nothing depends on which thread ran what, so the result is
// bit-identical for any thread count.
#include <atomic>
#include <cstdint>
#include <vector>

#include "assess/simulator.hpp"
#include "assess/statistics.hpp"
#include "assess/tally.hpp"

namespace j232::assess {

struct MarkRow {
  std::uint32_t replicate = 0;
  std::uint32_t nail = 0;
  flight::MarkRecord mark;
};

struct Assessment {
  std::vector<ReplicateTally> tallies;  // in replicate order
  std::vector<MarkRow> marks;           // in (replicate, nail) order; located marks only
  Histogram exit_speed{0.5, 400};       // m/s, 0.5 m/s bins to 200 m/s
  Histogram mark_energy{0.05, 600};     // J, 0.05 J bins to 30 J: marks only
  Histogram board_energy{0.05, 600};    // J: every first arrival at the board, marked or not
  Histogram board_energy_per_width{5, 400};  // J/m, 5 J/m bins to 2000 J/m
  Histogram contact_radius{0.005, 400}; // m
  std::uint64_t nails = 0, struck = 0, queries = 0, unlocated_marks = 0;
  double wall_seconds = 0;
  int threads = 0;
};

struct Progress {
  std::atomic<long long> done{0};
  std::atomic<long long> total{0};
};

// Runs the scenario's replicates (or, with a target half-width, batches until the
// P(pass) interval is that narrow or max_replicates is reached).
Assessment run_assessment(const Simulator& simulator, int threads, Progress* progress = nullptr);

// Replicates [first, first + count) appended to `into` (used by run_assessment and tests).
void run_replicates(const Simulator& simulator, std::uint64_t first, std::uint64_t count, Assessment& into,
                    Progress* progress);

}  // namespace j232::assess
