#pragma once
// Field designs compared (`j232 compare` of field scenarios, docs/model.md §9.3): every
// design meets the same objects in turn (object i of each is drawn from the same seed and
// index, its flight's random events keyed by their number), so each figure's difference
// from the first design is judged object by object: paired, far tighter than two separate
// runs would give. Figures per km mowed: objects thrown, objects first coming down outside
// the deck, hazardous ground impacts, and each plane's crossings and hazardous crossings.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "assess/runner.hpp"  // assess::Progress
#include "field/hazard_run.hpp"
#include "scenario/scenario.hpp"

namespace j232::field {

struct FieldFigure {
  std::string name;
  Estimate per_km;
};
struct FieldDifference {
  std::string name;
  Estimate per_km;                    // this design's figure minus the first's (normal, from the paired differences)
  std::uint64_t objects_differing = 0;  // objects whose own counts differ between the two
};
struct FieldDesign {
  std::string file, title;
  std::vector<FieldFigure> figures;
  std::vector<FieldDifference> differences;  // against the first design (empty for it)
  HazardSummary hazard;  // its own run's whole summary (hazard distances, P(struck), planes), as j232 hazard gives it
  double range = 0;                   // m: its tally's range (a hazard distance beyond it is only "beyond")
  double acceptable_probability = 0;  // of a person struck in one pass: one hazardous impact per acceptable area
};
struct FieldComparison {
  std::vector<FieldDesign> designs;
  std::uint64_t objects = 0;
  unsigned long long seed = 0;
  double wall_seconds = 0;
};

// Every design a field scenario; planes matched by name (each design must have the first's).
// Runs the first design's field.objects_simulated objects in each, design after design on
// the one runner (field::run_hazard_objects, as j232 hazard runs them, each object's own
// counts kept), a segment of kSegmentObjects at a time (one for the shipped runs), and adds
// the objects' values in object order into one assess::PairedSums, as a J232 comparison adds
// its replicates. Deterministic for any thread and MPI rank count; in an MPI job only rank 0's
// comparison holds the figures (the others' are empty: only rank 0 reports).
// `on_design(d, design, first, count, objects)` is told before each design's run of objects
// [first, first + count) of `objects`. (`segment_objects`: the segment, rounded to whole
// chunks; the results are the same whatever it is, tested.)
inline constexpr std::uint64_t kSegmentObjects = 262144;
FieldComparison compare_fields(
    const std::vector<scenario::Scenario>& designs, int threads, assess::Progress* progress = nullptr,
    const std::function<void(std::size_t, const scenario::Scenario&, std::uint64_t, std::uint64_t, std::uint64_t)>& on_design = {},
    std::uint64_t segment_objects = kSegmentObjects);

}  // namespace j232::field
