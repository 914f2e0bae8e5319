#pragma once
// The pages `j232 batch` writes over many scenarios: summary.json, summary.csv and
// summary.html, one row per scenario (verdict, P(pass) and interval, the four mean
// shares, a link to its report), or the error that stopped it; a field scenario's row
// gives its hazard distances and planes instead (a table of their own on the page).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace j232::report {

struct BatchRow {
  std::string scenario;                          // file as given
  std::string folder;                            // results folder, relative to the batch folder
  std::optional<nlohmann::ordered_json> result;  // result.json; absent when the scenario was refused
  std::optional<nlohmann::ordered_json> hazard;  // hazard.json of a field scenario (j232 hazard), instead of a result
  std::string error;                             // why it was refused
  bool resumed = false;                          // results were complete and current; not rerun
};

// `comparison`: compare.json of the scenarios run with common random numbers (batch
// --compare), carried under "comparison" and drawn at the end of the page; null: none.
nlohmann::ordered_json batch_summary_json(const std::vector<BatchRow>& rows, const nlohmann::ordered_json& comparison = nullptr);
std::string batch_summary_csv(const std::vector<BatchRow>& rows);
std::string batch_summary_html(const std::vector<BatchRow>& rows, const nlohmann::ordered_json& comparison = nullptr);

}  // namespace j232::report
