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
std::string comparison_html(const nlohmann::ordered_json& c);

}  // namespace j232::report
