#pragma once
// What most moves the verdict (study::deciding_drivers), in result.json ("deciding_inputs"),
// on the terminal and in report.html: the three inputs whose range moves the deciding
// criterion most, each with its basis (a source, or "estimate"), every end's share and its
// paired change against the scenario as written.
#include <nlohmann/json.hpp>
#include <string>
#include "study/drivers.hpp"

namespace j232::report {
inline constexpr std::size_t kDriversShown = 3;  // in the report and on the terminal; result.json has all
nlohmann::ordered_json drivers_json(const study::Drivers& d, const std::string& criterion);
std::string drivers_text(const nlohmann::ordered_json& deciding_inputs);
// Its section of report.html, from result.json's "deciding_inputs" (empty when absent).
std::string drivers_html(const nlohmann::ordered_json& result);
}  // namespace j232::report
