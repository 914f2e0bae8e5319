#pragma once
// A hazard run (`j232 hazard`, docs/model.md §9): the field's objects simulated in
// parallel, tallied, and turned into what a safety engineer reads: densities of hazardous
// impacts against distance in each direction with their intervals, the probability of a
// person being struck, the hazard distances, and each plane's hazardous flux.
#include <algorithm>
#include <atomic>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "assess/paired_runs.hpp"  // assess::UnitSink
#include "assess/runner.hpp"  // assess::Progress
#include "field/field_simulator.hpp"
#include "field/hazard_tally.hpp"

namespace j232::field {

struct HazardRun {
  std::vector<HazardTally> strata;  // one tally per stratum of objects (FieldSimulator::stratum: a kind's size range)
  std::uint64_t objects() const;
  double wall_seconds = 0;
  int threads = 1;
};

// What a paired comparison of designs (field::compare_fields) records of each object beside
// the tallies: `width` numbers, filled by `count` as the object's flight ends (its outcome and
// its watch's own counts), and handed to `sink` in object order (on rank 0 of an MPI job) as
// the runner merges the chunks: a J232 run's replicate sink, for a field's objects.
struct ObjectRows {
  std::size_t width = 0;
  std::function<void(const ObjectOutcome&, const ObjectWatch&, double* row)> count;
  assess::UnitSink sink;
};

// Simulates scenario.field.objects_simulated objects (0..N-1) on `threads` threads (0: all
// cores), shared out among the ranks of an MPI job (every rank ends with the whole tally).
// Bit-identical for any thread and rank count. `rows`: each object's row for a comparison.
HazardRun run_hazard(const FieldSimulator& sim, int threads, assess::Progress* progress = nullptr, const ObjectRows* rows = nullptr);
// Objects [first, first + count) of a run of `objects` in all (`first` a multiple of
// objects_per_chunk(objects), so the chunks are the whole run's), merged into `into`, which
// holds objects [0, first) already: what run_hazard does over every object, but for the
// whole-run tallies on every rank of an MPI job (here rank 0 alone holds them). A comparison
// runs its designs' objects a segment at a time with it, holding one segment's rows.
void run_hazard_objects(const FieldSimulator& sim, std::uint64_t objects, std::uint64_t first, std::uint64_t count, HazardRun& into,
                        int threads, assess::Progress* progress = nullptr, const ObjectRows* rows = nullptr);
// An empty run of the scenario's tallies (a tally per stratum), for run_hazard_objects.
HazardRun empty_run(const FieldSimulator& sim);

// A rate per metre travelled from the strata's per-object counts: the sum over strata of
// w_k S_k / N_k (w_k: the stratum's objects met per metre that can reach a blade, N_k its
// objects simulated), with a 95 % interval. The per-object counts' squares give the
// variance V = sum (w_k / N_k)^2 Q_k; the interval is Fay and Feuer's gamma interval for a
// weighted sum of counts (quasi_poisson): honest at zero, for objects that strike more than
// once, and when the stratum of the heaviest weight saw nothing.
struct Estimate {
  double value = 0, low = 0, high = 0;
  double variance = 0;  // of the value, from the per-object counts (V above): its Monte Carlo noise
  Estimate scaled(double f) const { return {value * f, low * f, high * f, variance * f * f}; }
};
struct Stratum {
  CountSum counts;
  double weight_per_object = 0;  // w_k / N_k
  bool possible = true;          // its objects can make the event counted (energy_bound above the threshold)
};
Estimate combined(const std::vector<Stratum>& strata);
// The heaviest weight per object among the strata that can make the event (`possible`) or
// did make it (counts.sum > 0; the squares are not read): what one more event could add, the
// widening of the interval's upper end for what a run may have missed.
double heaviest_weight(const std::vector<Stratum>& strata);
// The same interval from an estimate's mean and variance and the largest weight one event
// can carry (Fay and Feuer's gamma interval).
Estimate quasi_poisson(double mean, double variance, double heaviest);

// One direction's curve: at each distance, the density of hazardous impacts a person there
// meets in one pass of the mower (per m^2), and the probability of being struck.
struct DirectionCurve {
  std::string direction;  // "left", "right", "front", "rear"
  std::string meaning;    // what a point of the curve is, in words
  double deck_extent = 0;         // m: the deck reaches this far in this direction; the curve starts beyond it
  std::vector<double> distance;  // m
  std::vector<Estimate> density;     // hazardous ground impacts per m^2 per pass
  std::vector<Estimate> vertical;    // beside the path: hazardous crossings per m^2 of the vertical plane there, per pass
  std::vector<Estimate> exposure;    // the larger of the two (ahead, behind: the ground's): what a person there meets
  std::vector<Estimate> probability;  // of a person there being struck, 1 - exp(-exposure A)
  // Where the density falls below the acceptable one for good (estimate; on the interval's
  // upper end: the conservative one); beyond_range when it never does within the range.
  double hazard_distance = 0, hazard_distance_upper = 0;
  bool beyond_range = false, upper_beyond_range = false;
  // The same at other acceptable densities (kSetbackFactors times the scenario's): how the
  // setback moves with what is judged acceptable.
  struct Setback {
    double acceptable_density = 0;  // per m^2 per pass
    double estimate = 0, conservative = 0;
    bool beyond_range = false, conservative_beyond_range = false;
  };
  std::vector<Setback> setbacks;
};
// The acceptable densities the setbacks are given at, as multiples of the scenario's: ten
// times stricter to ten times laxer, by half decades.
inline constexpr double kSetbackFactors[] = {0.1, 0.316227766016838, 1.0, 3.16227766016838, 10.0};

struct PlaneResult {
  scenario::FieldPlaneSpec plane;
  double crossings_per_km = 0;
  Estimate hazardous_per_km;    // within the receptor's band, with at least its energy
  Estimate hazardous_per_area;  // per m^2 of the band, per pass (a person standing at the plane)
  Estimate probability;         // person: struck in one pass, 1 - exp(-flux A); vehicle: empty
  // person: over the season's passes (field.passes_per_season), a person there every pass
  // struck at least once, 1 - (1 - p)^passes; and the people struck per season when
  // field.people_per_pass stand there each pass, passes x people x p
  Estimate probability_per_season, people_struck_per_season;
  bool along_path = true;       // left or right: the per-area figures hold; ahead or behind: per km only
  std::vector<double> per_km_by_height;  // every crossing, by 0.25 m band
};

struct HazardSummary {
  double objects_per_metre = 0, objects_per_km = 0, cut_width = 0;
  double reaching_per_km = 0;  // objects met per km whose size lets them reach a blade
  double acceptable_density = 0;  // per m^2
  std::uint64_t objects = 0, thrown = 0, cut_off = 0;
  double cut_off_share = 0;
  bool valid = true;         // few enough objects cut off by the run's limits (below 1 %)
  std::string invalid_reason;
  std::string cut_off_limits;  // "12 by run.time_limit, 3 by a wedge ...": what cut objects off, in the order of the limits
  std::vector<std::string> warnings;  // the reader's notes, and cut-offs from 0.25 % (below the 1 % that withholds the answer)
  std::vector<DirectionCurve> directions;
  std::vector<PlaneResult> planes;
  double thrown_per_km = 0, landed_outside_deck_share = 0, max_distance = 0;
  double thrown_per_km_variance = 0;  // its Monte Carlo noise: each stratum's thrown share is binomial
  double exit_speed_mean = 0, exit_speed_q95 = 0, launch_elevation_mean = 0;
  double last_strike_speed_mean = 0, last_strike_speed_q95 = 0;  // off the last blade strike (the speed objects leave with)
};
HazardSummary summarise(const FieldSimulator& sim, const HazardRun& run);
// What the run counted of one kind: its strata's tallies merged (whole counts of the objects
// simulated, not weighted).
HazardTally kind_tally(const FieldSimulator& sim, const HazardRun& run, std::size_t kind);
// Each stratum's weight per simulated object (w_k / N_k, per metre travelled).
std::vector<double> weights_per_object(const FieldSimulator& sim, const HazardRun& run);
// The same for a run of `objects` objects: object i is of stratum i mod strata, so stratum k
// has objects / strata of them, one more for the first objects mod strata strata.
std::vector<double> weights_per_object(const FieldSimulator& sim, std::uint64_t objects);
// Objects per task of a parallel run of n objects: 256, fewer in a small run (an uncertainty
// study's hundreds at each draw), so that its eight or more tasks keep both cores busy. A
// function of n alone: the run is the same on any number of threads.
inline std::uint64_t objects_per_chunk(std::uint64_t n) { return std::clamp<std::uint64_t>((n + 7) / 8, 32, 256); }
// Chunks in flight at once on a rank, each holding `bytes_per_slot` (a tally per stratum and
// design: the ground's grid, some 0.7 MB at the default range and cell, up to 64 MB at the
// finest): eight per thread, so that the chunks' uneven times even out, fewer when they would
// hold more than 512 MB together, but never fewer than one per thread (the memory a run on
// per-thread tallies would need anyway).
std::uint64_t slots_per_wave(std::size_t bytes_per_slot, int threads);

}  // namespace j232::field
