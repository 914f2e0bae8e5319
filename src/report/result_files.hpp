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
  struct File {
    std::string name;
    std::uint64_t bytes = 0;
    std::string fnv1a64;
  };
  std::vector<File> files;  // the run's other output files: a reader can check the set is whole
  int ranks = 1;            // processes of an MPI job, each with `threads` threads
};

nlohmann::ordered_json result_json(const scenario::Scenario& s, const assess::Assessment& a, const assess::Summary& sum,
                                   const Provenance& provenance);
// marks.csv is written as the run goes (its rows arrive in order from the runner's sink).
std::string marks_csv_header();
// `sim` names each mark's exit path (its openings and guards).
void append_marks_csv_row(std::string& out, const assess::MarkRow& row, const assess::Simulator& sim);

// How the scenario departs from SAE J232's own rules (limits, counted height), in words.
std::vector<std::string> departures_from_j232(const scenario::Scenario& s);

// The verdict word of a run: "passes", "fails", or "invalid" (the test did not happen).
const char* verdict_word(const assess::Summary& sum);

// The text of a JSON file j232 writes (or a page embeds): every real number rounded to 12
// significant digits, then written in its shortest round-trip form, so a length of 30 reads
// 30 and not 29.999999999999996 (binary noise of the arithmetic that made it); indented by
// `indent` (-1: on one line). Rounding twice changes nothing, so a result read back and
// written again is the same text.
std::string json_text(const nlohmann::json& j, int indent = 2);
std::string json_text(const nlohmann::ordered_json& j, int indent = 2);
// The JSON as a reader of its saved file gets it (json_text's numbers read back): a page drawn
// from it is the saved file's page, and a number that is not finite (written as null) stops
// the page being drawn instead of reaching it.
nlohmann::ordered_json as_saved(const nlohmann::ordered_json& j);

// Throws std::logic_error naming the first non-finite number in `j` (a bug: every
// number a result holds must be finite).
void require_finite(const nlohmann::ordered_json& j, const std::string& where = "");

// A few lines for the terminal: verdict, P(pass) and interval, the four shares.
std::string summary_text(const scenario::Scenario& s, const assess::Summary& sum);

}  // namespace j232::report
