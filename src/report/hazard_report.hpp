#pragma once
// What `j232 hazard` writes (docs/model.md §9): hazard.json (every figure with its
// interval, the plan views as drawn, the inputs and the provenance), hazard.csv (the curves,
// a row a point) and hazard.html (the plan views of where objects land, the curves, the
// hazard distances, the planes, the assumptions with their sources), drawn from hazard.json.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "field/field_compare.hpp"
#include "field/field_simulator.hpp"
#include "field/hazard_run.hpp"
#include "report/display_units.hpp"
#include "report/scenario_json.hpp"

namespace j232::report {

struct HazardProvenance {
  std::string version, git_revision, date;
  std::uint64_t seed = 0;
  int threads = 1;
  int ranks = 1;  // processes of an MPI job, each with `threads` threads
  double wall_seconds = 0;
};

// The assumptions a hazard report names, each with its source.
std::vector<Assumption> hazard_assumptions(const scenario::Scenario& s);

nlohmann::ordered_json hazard_json(const field::FieldSimulator& sim, const field::HazardRun& run, const field::HazardSummary& sum,
                                   const HazardProvenance& p);
std::string hazard_csv(const field::HazardSummary& sum);
// The page, from hazard.json alone (`result`: hazard_json's, as saved), in the units `u`
// names (SI by default). Throws nlohmann::json's errors on a file without what it draws (one
// written before its plan views were kept).
std::string hazard_html(const nlohmann::ordered_json& result, const DisplayUnits& u = {});
// The terminal's summary: the hazard distances and the planes, with their intervals (`range`:
// the field's, as hazard.json's range_m, which a distance past the curves is said to be beyond).
std::string hazard_text(const field::HazardSummary& sum, double range, const DisplayUnits& u = {});

// Field designs compared (j232 compare of field scenarios): compare.json, .csv, .html and
// the terminal's table. The page is drawn from compare.json alone (`c`: hazard_comparison_json's,
// as saved), so a saved comparison draws the same page.
nlohmann::ordered_json hazard_comparison_json(const field::FieldComparison& c);
std::string hazard_comparison_csv(const field::FieldComparison& c);
std::string hazard_comparison_html(const nlohmann::ordered_json& c, const DisplayUnits& u = {});
std::string hazard_comparison_text(const field::FieldComparison& c, const DisplayUnits& u = {});

}  // namespace j232::report
