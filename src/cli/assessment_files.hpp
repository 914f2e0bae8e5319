#pragma once
// One assessment from scenario file to result folder: result.json, marks.csv and
// report.html, each written whole or not at all (result.json last, so its presence
// means the folder is complete). Shared by `j232 run` and `j232 batch`.
#include <nlohmann/json.hpp>
#include <string>

namespace j232::cli {

struct RunOverrides {
  long long replicates = 0;  // 0: the scenario's
  long long seed = -1;       // < 0: the scenario's
  int threads = -1;          // < 0: the scenario's
};

struct RunOutcome {
  nlohmann::ordered_json result;  // what result.json holds
  std::string summary_text;       // the terminal summary
};

// A fingerprint of everything a result depends on: the scenario file's and its mesh
// files' bytes, the overrides and the program's version and revision.
std::string inputs_digest(const std::string& scenario_file, const RunOverrides& overrides);

// Throws scenario::InputError for bad input. Draws a progress bar when stderr is a terminal.
RunOutcome assess_to_folder(const std::string& scenario_file, const RunOverrides& overrides, const std::string& out);

}  // namespace j232::cli
