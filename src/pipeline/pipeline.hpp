#pragma once
// The two pipelines the studies run (docs/architecture.md): the J232 test (replicates of
// the whole test, judged against its pass criteria) and the field (objects met along a
// pass, judged by the hazard around the mower). A study asks its scenario's Pipeline for
// what differs between them (the outputs judged at a draw, the estimated inputs, one
// assessment, what its warnings say, a sweep's columns and points) instead of which one it
// has; `pipeline_of` is the one place that looks, and `kind()` only names it for the
// reports (uq.json's "kind", a sweep table's).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "scenario/scenario.hpp"
#include <toml++/toml.h>

namespace j232::pipeline {

// An output judged at each draw of a study: its uq.json key, its name on the page and how
// it is shown.
struct Output {
  std::string name, words;
  enum class Scale { Probability, Percent, Number } scale = Scale::Number;  // Percent: a share shown in %
  std::string unit;  // after a Number: " m", " per km"
};

// One assessment at a draw: its outputs (as Pipeline::outputs), and the share of its struck
// nails (thrown objects) that the run's limits cut off with the commonest of those limits
// (flight::CutOff), for its warnings.
struct DrawOutputs {
  std::vector<double> outputs;
  double cut_off_share = 0;
  int cut_off_limit = 0;
};

// How large each assessment of a study is: replicates of the J232 test, objects of a field.
struct DrawSize {
  long long replicates = 50;
  long long objects = 0;
};

// A sweep's columns as a pipeline fills them (study::SweepTable keeps them): the first point
// assessed may add its own (a field's directions and planes).
struct SweepColumns {
  std::vector<std::string> columns;
  std::vector<std::string> planes, directions;  // a field's, as its first point assessed named them
  double required_pass_probability = 0;         // a J232 test's
};
// A sweep point that breaks the whole sweep (a field's planes that differ from its first
// point's): the sweep stops with it, naming the point.
struct BrokenSweep : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};
// A setting a sweep file may not give this pipeline: its key, its value and why.
struct Refusal {
  std::string key, value, why;
};

class Pipeline {
 public:
  virtual ~Pipeline() = default;
  enum class Kind { J232, Field };
  virtual Kind kind() const = 0;
  // What one assessment is, in a sentence naming an invalid draw ("the simulated test"), and
  // what its cut-off share is a share of ("struck nails").
  virtual const char* assessment_words() const = 0;
  virtual const char* cut_off_words() const = 0;

  // The outputs judged at each draw (the verdict, 1 or 0, last) and the smooth one whose
  // Sobol' indices rank the inputs.
  virtual std::vector<Output> outputs(const scenario::Scenario& s) const = 0;
  virtual std::size_t smooth_output(const scenario::Scenario& s, const std::vector<Output>& outputs) const = 0;
  // j232's estimated inputs with their ranges and bases (docs/model.md §8, or §9 for a field).
  virtual std::vector<scenario::UncertainInput> estimated_inputs(const scenario::Scenario& s) const = 0;
  // Why this pipeline's study cannot draw `key` (empty: as far as it knows, it can).
  virtual std::string cannot_vary(const std::string& key) const = 0;
  // The size of each assessment of the scenario's study ([uncertainty]).
  virtual DrawSize draw_size(const scenario::Scenario& s) const = 0;
  // One assessment of `draw` (the scenario with the drawn inputs) at `size`, with common
  // random numbers (the nominal scenario's seed, the same replicates or objects at every
  // draw). Sets `invalid` to the reason when the assessment may not be used. In an MPI job
  // every rank returns the same outputs.
  virtual DrawOutputs assess(scenario::Scenario& draw, const scenario::Scenario& nominal, const DrawSize& size, int threads,
                             std::string& invalid) const = 0;
  // Warnings about a draw's outputs beyond the cut-off share (`name`: how to name the draw).
  virtual void warn(const scenario::Scenario& nominal, const std::vector<Output>& info, const std::vector<double>& outputs,
                    const std::string& name, std::vector<std::string>& warnings) const = 0;
  // Why a named parameter of a study (a sweep's axis, an uncertain input: "restitution",
  // "cut_height") cannot be set on this pipeline's scenario `s` (empty: it can).
  virtual std::string refuse_parameter(const std::string& name, const scenario::Scenario& s) const = 0;
  // Why `j232 drivers` cannot rank this pipeline's inputs by a deciding criterion (empty: it can).
  virtual std::string refuse_drivers() const = 0;
  // A sweep over this pipeline: the columns every point has; the size of each point's run
  // (`size`: 0 for the scenario's own), refusing the one this pipeline does not take; one
  // point's values for the columns, or `invalid` set to why the point has none (the reader
  // refused what its settings make, or its run is invalid: the sweep records it and goes on).
  // Throws BrokenSweep for a point that breaks the sweep (a field's planes that differ from
  // its first point's). `first`: no point has been assessed yet.
  virtual std::vector<std::string> sweep_columns() const = 0;
  virtual std::optional<Refusal> refuse_sweep_size(const DrawSize& size) const = 0;
  virtual std::vector<double> sweep_point(scenario::Scenario& sc, const DrawSize& size, bool first, int threads, SweepColumns& t,
                                          std::string& invalid) const = 0;
  // Per output, the variance Monte Carlo noise alone would give it over the first
  // `base_runs` draws of `runs` (as if each draw met new nails or objects: common random
  // numbers make it less); -1 where not estimated. A pipeline may run the nominal scenario
  // at the draws' size to measure it (on `threads` threads).
  virtual std::vector<double> noise_variance(const scenario::Scenario& nominal, const DrawSize& size, const std::vector<Output>& info,
                                             const std::vector<std::vector<double>>& runs, std::size_t base_runs, int threads) const = 0;
};

// The scenario's pipeline: the field when it has a [field], else the J232 test; of a
// scenario file not yet read (a sweep's base, read again at each point), the same by its
// tables.
const Pipeline& pipeline_of(const scenario::Scenario& s);
const Pipeline& pipeline_of(const toml::table& scenario_file);

}  // namespace j232::pipeline
