#pragma once
// A result compared with an earlier one (`j232 compare EARLIER/result.json SCENARIO.toml`, or
// two result.json files): which physics produced each (model_version, the program's version),
// each verdict, and what moved - P(pass) and each criterion's share with the difference's 95 %
// interval. The two runs share no per-replicate record, so they are judged as independent
// samples (Newcombe's interval for two independent proportions); a rerun of the same model
// with the same seed reproduces the earlier result exactly, and says so.
#include <nlohmann/json.hpp>
#include <string>

namespace j232::report {

// Reads a result.json as j232 run writes it; throws scenario::InputError naming the file and
// the key when it is not one (or lacks what a comparison needs).
nlohmann::ordered_json read_result_file(const std::string& path);

// `before` and `now`: two results (read_result_file), `*_file` where they came from.
nlohmann::ordered_json compare_results(const nlohmann::ordered_json& before, const std::string& before_file,
                                       const nlohmann::ordered_json& now, const std::string& now_file);
std::string version_comparison_text(const nlohmann::ordered_json& c);
std::string version_comparison_html(const nlohmann::ordered_json& c);

}  // namespace j232::report
