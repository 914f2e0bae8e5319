#pragma once
// What `j232 compare` writes: compare.json (every number), compare.csv (one row per
// criterion and design) and compare.html (a table and a chart per criterion with the
// limit drawn; numbers tagged with their compare.json keys).
#include <nlohmann/json.hpp>
#include <string>

#include "study/compare.hpp"

namespace j232::report {

nlohmann::ordered_json comparison_json(const study::Comparison& c);
std::string comparison_csv(const study::Comparison& c);
// For the terminal: each design's verdict, P(pass) (both estimates) and deciding criterion
// with its margin, then each design's differences from design 1.
std::string comparison_text(const study::Comparison& c);
std::string comparison_html(const nlohmann::ordered_json& c);
// The page's body (designs, tables, a chart per criterion), its numbers keyed `prefix` + the
// key in `c`, for a page whose JSON holds `c` under a key (the batch summary's "comparison.").
std::string comparison_body_html(const nlohmann::ordered_json& c, const std::string& prefix);

}  // namespace j232::report
