#pragma once
// One assessment from scenario file to result folder: result.json, marks.csv and
// report.html, written as a set (report/output_folder.hpp: result.json's presence means the
// folder is complete). What `j232 run` and `j232 batch` do, for any program.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "study/compare.hpp"

namespace j232::report {

struct RunOverrides {
  long long replicates = 0;           // 0: the scenario's
  std::optional<std::uint64_t> seed;  // none: the scenario's
  int threads = -1;                   // < 0: the scenario's
  std::size_t trajectories = 0;       // sampled nail paths to keep (plus notable ones); 0: none
  bool uncertainty = false;           // also run the scenario's uncertainty study (run --uncertainty)
  bool drivers = false;               // also find the inputs that most move the deciding criterion (run --drivers)
  bool for_comparison = false;        // keep what a comparison of designs needs; no stop rule (batch --compare)
  bool until_settled = false;         // run.until_settled = true
  std::optional<double> target_half_width;  // none: the scenario's run.target_half_width
  std::optional<scenario::RunSpec::Estimator> estimator;  // none: the scenario's run.estimator
};

struct RunOutcome {
  nlohmann::ordered_json result;              // what result.json holds
  std::string summary_text;                   // the terminal summary
  std::optional<study::DesignRecord> design;  // with RunOverrides::for_comparison
};

// A fingerprint of everything a result depends on: the scenario file's and its mesh
// files' bytes, the overrides and the program's version and revision.
std::string inputs_digest(const std::string& scenario_file, const RunOverrides& overrides);

// Throws scenario::InputError for bad input and report::FileError when the folder cannot
// be written (checked before simulating). Draws a progress bar when stderr is a terminal.
RunOutcome assess_to_folder(const std::string& scenario_file, const RunOverrides& overrides, const std::string& out);

}  // namespace j232::report
