#pragma once
// The files `j232 run` writes: result.json (everything, deterministic apart from the
// "provenance" object) and marks.csv (one row per located mark).
#include <nlohmann/json.hpp>
#include <string>

#include "assess/summary.hpp"

namespace j232::report {

struct Provenance {
  std::string version, git_revision, date, inputs_digest;
  int threads = 0;
  double wall_seconds = 0;
};

nlohmann::ordered_json result_json(const scenario::Scenario& s, const assess::Assessment& a, const assess::Summary& sum,
                                   const Provenance& provenance);
std::string marks_csv(const assess::Assessment& a);

// A few lines for the terminal: verdict, P(pass) and interval, the four shares.
std::string summary_text(const scenario::Scenario& s, const assess::Summary& sum);

}  // namespace j232::report
