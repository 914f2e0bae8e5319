#pragma once
// Replicates of the whole test, in parallel on oneTBB (see docs/model.md, "Randomness
// and parallelism"). Work is cut into fixed chunks of replicates; chunks run in waves of
// a bounded number, each chunk filling its own tallies, and each wave is merged in chunk
// order before the next starts. Nothing depends on which thread ran what, so the result
// is bit-identical for any thread count; and nothing is kept per replicate, so memory
// does not grow with the number of replicates (marks are handed to a sink in order).
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "assess/simulator.hpp"
#include "assess/exact_pass.hpp"
#include "assess/statistics.hpp"
#include "assess/tally.hpp"

namespace j232::assess {

struct MarkRow {
  std::uint32_t replicate = 0;
  std::uint32_t nail = 0;
  flight::MarkRecord mark;
  // The nail's trail: where it was fed, its strikes, what it touched and how it left.
  std::uint16_t spindle = 0, station = 0;  // 0-based
  int strikes = 1;
  double flight_time = 0;  // s from the first strike to its end
  flight::NailTrace trace;
};

// How nails left the deck, for the counted marks: what to close (docs/model.md §5.8).
inline std::uint32_t exit_key(flight::Exit e, std::uint16_t index) { return static_cast<std::uint32_t>(e) << 16 | index; }
inline flight::Exit exit_of(std::uint32_t key) { return static_cast<flight::Exit>(key >> 16); }
inline std::uint16_t exit_index(std::uint32_t key) { return static_cast<std::uint16_t>(key & 0xFFFFu); }
struct ExitTable {
  static constexpr int kBands = 8;                                            // exit azimuth about the origin in 45 deg bands from -180 deg
  std::map<std::uint32_t, std::uint64_t> nails;                               // struck nails by exit path
  std::map<std::uint32_t, std::array<std::uint64_t, kBands>> marks;           // their counted marks, by exit band
  std::array<std::uint64_t, 5> marks_by_strikes{};                            // nails struck 1, 2, 3, 4, 5+ times
  std::array<std::uint64_t, flight::kTouchKinds + 1> marks_by_first_touch{};  // the last: straight to the board

  void add(const flight::FlightResult& f);
  void merge(const ExitTable& other);
};

// Receives every located mark, in (replicate, nail) order, as the merge reaches it.
using MarkSink = std::function<void(const MarkRow&)>;
// Receives every replicate's judgement (its four shares and pass), in replicate order:
// what paired comparisons of designs need (j232 compare).
using ReplicateSink = std::function<void(std::uint64_t replicate, const Judgement&)>;

// One criterion's share over replicates, exactly and in bounded memory: a share is a
// ratio of small counts, so it takes few distinct values however many replicates run.
struct ShareDistribution {
  std::map<double, std::uint64_t> counts;  // share -> replicates with it
  std::uint64_t total = 0;
  double sum = 0;  // summed in replicate order: deterministic

  void add(double share);
  double mean() const { return total ? sum / static_cast<double>(total) : 0.0; }
  // Hyndman & Fan type 7, as quantile_sorted() over every replicate's share.
  double quantile(double p) const;
};

// What a run records of every nail, whatever its replicate: fixed-bin distributions, the
// exit table, the outcomes by feed station and counts, so merging chunks is exact and
// order-free. A chunk's and the whole run's are the same set.
struct NailRecords {
  Histogram exit_speed{0.5, 1200};           // m/s as the nail leaves the blade, 0.5 m/s bins to 600 m/s (beyond any blade)
  Histogram launch_elevation{1, 180, -90};   // deg, its elevation then, 1 deg bins from -90 to 90
  Histogram contacts_per_pass{1, 33};        // blade contacts in each pass: bin k holds k contacts (32: 32 or more)
  Largest most_contacts_in_pass;             // the pass of most contacts of any struck nail
  Histogram mark_energy{0.05, 600};          // J, 0.05 J bins to 30 J: marks only
  Histogram board_energy{0.05, 600};         // J: every first arrival at the board, marked or not
  Histogram board_energy_per_width{5, 400};  // J/m, 5 J/m bins to 2000 J/m
  Histogram contact_radius{0.005, 400};      // m
  Histogram strikes{1, 52};                  // blade strikes per struck nail: bin k holds k strikes (51: 51 or more)
  Largest most_strikes;                      // the most strikes of any struck nail
  Histogram cut_off_by{1, flight::kCutOffReasons};  // cut-off nails by the limit that cut them off: bin k holds flight::CutOff(k)
  ExitTable exits;
  StationOutcomes outcomes;  // every nail fed: its counted marks by category, by feed station (the exact P(pass))
  std::uint64_t nails = 0, struck = 0;
  std::uint64_t queries = 0;          // the scene's queries (a chord's broad phase, a mark's label)
  // The flights' events, for the benchmark: bounces, gentle contacts, and those of either on a
  // wall (flight::FlightResult::wall_contacts). (Blade strikes: the `strikes` histogram's mean.)
  std::uint64_t bounces = 0, gentle_contacts = 0, wall_contacts = 0;
  std::uint64_t unlocated_marks = 0;  // marks whose point on the board was not found
  std::uint64_t non_finite = 0;       // nails whose state stopped being a number

  // Every record of two in step, once: merge, pack and unpack (MPI) go through it, so none
  // of them can miss a record another has; a new record is added here and in the struct
  // alone. `f(a, b)` is called with each record of `a` and the same record of `b`: a
  // Histogram, the Largest, the ExitTable, the StationOutcomes or a count.
  template <class A, class B, class F>
  static void zip(A& a, B& b, F&& f) {
    f(a.exit_speed, b.exit_speed);
    f(a.launch_elevation, b.launch_elevation);
    f(a.contacts_per_pass, b.contacts_per_pass);
    f(a.most_contacts_in_pass, b.most_contacts_in_pass);
    f(a.mark_energy, b.mark_energy);
    f(a.board_energy, b.board_energy);
    f(a.board_energy_per_width, b.board_energy_per_width);
    f(a.contact_radius, b.contact_radius);
    f(a.strikes, b.strikes);
    f(a.most_strikes, b.most_strikes);
    f(a.cut_off_by, b.cut_off_by);
    f(a.exits, b.exits);
    f(a.outcomes, b.outcomes);
    f(a.nails, b.nails);
    f(a.struck, b.struck);
    f(a.queries, b.queries);
    f(a.bounces, b.bounces);
    f(a.gentle_contacts, b.gentle_contacts);
    f(a.wall_contacts, b.wall_contacts);
    f(a.unlocated_marks, b.unlocated_marks);
    f(a.non_finite, b.non_finite);
  }
  void merge(const NailRecords& other);
};

// The marks of the first replicates, for pictures: whole replicates (a fair sample, as
// replicates are independent), as many as fit in kMarkSample marks (at least one).
inline constexpr std::size_t kMarkSample = 3000;

// A nail's whole path, kept for pictures (assess/trajectories.hpp).
struct Trajectory {
  std::uint64_t replicate = 0;
  int nail = 0;
  std::string why;  // "sample", "operator zone", "puncture"
  flight::Fate fate = flight::Fate::OverBoard;
  std::vector<flight::Vec3> points;
};

struct Assessment : NailRecords {
  std::uint64_t replicates = 0, passed = 0;
  std::array<std::uint64_t, kCategories> criterion_passed{};
  std::array<ShareDistribution, kCategories> shares;
  std::uint64_t marks = 0;            // counted marks, located or not
  std::uint64_t uncounted_marks = 0;  // marks below the counted height
  std::array<std::uint64_t, flight::kFates> fates{};

  std::vector<MarkRow> mark_sample;          // in (replicate, nail) order
  std::uint64_t mark_sample_replicates = 0;  // replicates 0 .. this-1 are in the sample
  bool mark_sample_closed = false;           // a replicate did not fit: no later one is added

  double wall_seconds = 0;
  int threads = 0;
  // With a stop rule (run.target_half_width, run.until_settled): how many times the
  // estimate was looked at, and what stopped the batches ("target_half_width", "settled",
  // "max_replicates"); empty without one.
  int looks = 0;
  std::string stopped_by;
  std::map<std::uint32_t, std::string> exit_names;  // every exit path in `exits` and first exit in the mark sample, in words
  // Filled after the run when asked for (run --trajectories): chosen nails' paths, and how
  // many notable nails (zone marks, punctures) were not kept beyond the cap.
  std::vector<Trajectory> trajectories;
  std::uint64_t trajectories_not_kept = 0;
};

struct Progress {
  std::atomic<long long> done{0};
  std::atomic<long long> total{0};  // with a stop rule: the end of the batch under way
  std::atomic<int> looks{0};        // a stop rule's looks so far (0: none, or no stop rule)
};

// Runs the scenario's replicates (or, with a stop rule, batches until the verdict's P(pass)
// interval is narrow enough or settled, or max_replicates is reached).
Assessment run_assessment(const Simulator& simulator, int threads, Progress* progress = nullptr, const MarkSink& marks = {},
                          const ReplicateSink& replicates = {});

// Replicates [first, first + count) merged into `into`, which must hold replicates
// [0, first) already (used by run_assessment and tests).
void run_replicates(const Simulator& simulator, std::uint64_t first, std::uint64_t count, Assessment& into, Progress* progress,
                    const MarkSink& marks = {}, const ReplicateSink& replicates = {});

}  // namespace j232::assess
