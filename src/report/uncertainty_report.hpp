#pragma once
// What `j232 uq` writes: uq.json (every number), uq.csv (one row per assessment: the
// inputs drawn and the outputs) and uq.html (the robust verdict, the outputs'
// distributions over the inputs' uncertainty, and Sobol' index charts; numbers tagged
// with their uq.json keys).
#include <nlohmann/json.hpp>
#include <string>

#include "study/uncertainty.hpp"

namespace j232::report {

nlohmann::ordered_json uncertainty_json(const study::UncertaintyResult& r);
std::string uncertainty_csv(const study::UncertaintyResult& r);

// A finished study's uq.csv read back exactly (its numbers are written to round-trip):
// the column names and, per assessment, its inputs drawn and its outputs with the cut-off
// share. A file that is not such a table is refused with its line and column
// (scenario::InputError).
struct UncertaintyTable {
  std::string file;
  std::vector<std::string> columns;  // after assessment and block, before the cut-off columns
  std::vector<std::vector<double>> cells;  // per assessment: one number per column
  std::vector<study::UqRun> runs;          // per assessment: cut_off_share and limit (outputs filled by split)
  std::vector<int> lines;                  // per assessment: its line in the file
};
UncertaintyTable read_uncertainty_csv(const std::string& path);
std::string uncertainty_html(const nlohmann::ordered_json& j);
// What a compliance report carries of a study run beside it (run --uncertainty): the robust
// verdict, P(pass) over the inputs, and the inputs ranked by their total index for P(pass).
nlohmann::ordered_json uncertainty_summary_json(const nlohmann::ordered_json& study);
std::string uncertainty_summary_text(const nlohmann::ordered_json& summary);
// Its section of report.html, from result.json's "uncertainty".
std::string uncertainty_summary_html(const nlohmann::ordered_json& result);

}  // namespace j232::report
