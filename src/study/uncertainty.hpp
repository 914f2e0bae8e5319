#pragma once
// How much a verdict rests on estimated inputs (docs/model.md §6b): the scenario's
// uncertain inputs ([uncertainty], or j232's default set of its estimated inputs) drawn by
// the Saltelli scheme from a Sobol' sequence, a whole assessment at each draw with common
// random numbers (one seed for all), and what comes of it: the distribution of P(pass) and
// of each share over the inputs' uncertainty, the share of draws in which the mower
// passes (a robust verdict), and Sobol' indices ranking the inputs for each. A field
// scenario's study runs a hazard run at each draw, over the same objects, and judges its
// rates, hazard distances and planes (docs/model.md §9).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "assess/tally.hpp"
#include "pipeline/pipeline.hpp"
#include "scenario/scenario.hpp"
#include "study/sensitivity.hpp"

namespace j232::study {

// The inputs studied, with their ranges: the scenario's own, or the defaults (estimated
// inputs of docs/model.md §8, or for a field those of §9, with ranges and their bases).
// `defaults` says which. A J232 test's assessments run `replicates` replicates each; a
// field's simulate `objects` objects each.
struct UncertaintyPlan {
  std::vector<scenario::UncertainInput> inputs;
  bool defaults = false;
  std::size_t base_draws = 256;
  long long replicates = 50;
  long long objects = 0;  // a field scenario's objects per assessment (0: not a field)
  pipeline::DrawSize size() const { return {replicates, objects}; }
};
UncertaintyPlan uncertainty_plan(const scenario::Scenario& s);
// The scenario (`base`, read from `file`) with input `in` set to `text` as a study sets it: a
// file key written into the document before it is read, a named parameter onto the result.
// Throws InputError naming `where` when the reader or the parameter refuses the value.
scenario::Scenario scenario_with(const toml::table& base, const std::string& file, const scenario::UncertainInput& in,
                                 const std::string& text, const std::string& where);
// "restitution = 0.62, crush_depth = 1.2 mm": a draw's inputs (`values`, one per input of the
// plan; a discrete input's index into its values), each number with the unit its range was
// written in, as warnings and refusals name a draw.
std::string draw_inputs(const UncertaintyPlan& plan, const std::vector<double>& values);

// An output judged at each draw: its uq.json key, its name on the page and how it is shown.
using UqOutput = pipeline::Output;

// A J232 test's outputs: P(pass) (the share of passing replicates, and from every nail:
// smooth, so its Sobol' indices mean something), the four mean shares, and whether it passes.
// A field's: objects thrown per km, the hazard distance in each direction, each plane's
// hazardous flux (and a person's probability of being struck there), and whether the ground
// beyond the deck is acceptable. The verdict, 1 or 0, is always the last output.
std::vector<UqOutput> uq_outputs(const scenario::Scenario& s);

// One assessment of the study: its outputs, and the share of its struck nails (thrown
// objects) that the run's limits cut off with the commonest of those limits.
using UqRun = pipeline::DrawOutputs;

struct UncertaintyResult {
  UncertaintyPlan plan;
  std::string scenario_file, title;
  unsigned long long seed = 0;
  bool field = false;      // a field scenario's study (j232 hazard at each draw)
  double required = 0.9;   // a J232 test's required P(pass)
  double acceptable_area = 0;  // a field's: one hazardous impact per this many m^2 is acceptable
  std::vector<UqOutput> output_info;
  std::size_t smooth_output = 1;  // the output whose indices rank the inputs (P(pass) from every nail; a field's first flux)
  SaltelliDesign design;
  std::vector<std::vector<double>> values;   // per run, per input: the value set (SI or the number written)
  std::vector<std::vector<double>> outputs;  // per run, per output (as output_info)
  std::vector<SobolIndices> indices;         // per output
  // From the first half of the base draws: the check that N is enough (none below N = 4).
  std::optional<std::vector<SobolIndices>> half_indices;
  // Per output: the variance Monte Carlo noise alone would give it over the base draws
  // (binomial, as if each draw met new nails; common random numbers make it less): a share
  // of the nails fed p(1-p)/(R n), the replicates' P(pass) p(1-p)/R; -1 where not estimated
  // (P(pass) from every nail, a verdict, a field's figures, shares of the marks).
  std::vector<double> noise_variance;
  std::vector<UqRun> runs;  // per run: outputs (as `outputs`) and cut-off share
  // A draw whose cut-off share neared the invalidity limit, naming the draw's inputs and
  // the limit that cut its nails off, one sentence each.
  std::vector<std::string> warnings;
};

// An input's distribution over [low, high], in the numbers written (their unit aside).
struct InputDistribution {
  enum class Kind { Uniform, Triangular, Normal, LogUniform } kind = Kind::Uniform;
  double low = 0, high = 1;
  double mode = 0.5;  // Triangular
  double sd = 0.25;   // Normal (truncated to [low, high], about the midpoint)
  // The value at probability u in (0, 1): the inverse of the distribution function, so a
  // uniform point of the Sobol' design becomes a draw from this distribution.
  double quantile(double u) const;
};

// Where a study keeps the outputs of the assessments it has finished, so that an
// interrupted study can resume (`j232 uq --resume`): `recall(i)` gives run i's outputs if
// they were recorded, `record(i, outputs)` is told each newly finished run. Outputs are
// kept exactly, so a resumed study gives the same result, bit for bit.
struct UncertaintyJournal {
  std::function<std::optional<UqRun>(std::size_t)> recall;
  std::function<void(std::size_t, const UqRun&)> record;
};

// Runs the study of the scenario file. `on_run(i, n)` is told before run i of n.
UncertaintyResult run_uncertainty(const std::string& scenario_file, int threads,
                                  const std::function<void(std::size_t, std::size_t)>& on_run = {},
                                  const UncertaintyJournal* journal = nullptr);

}  // namespace j232::study
