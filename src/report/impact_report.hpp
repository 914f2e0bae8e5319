#pragma once
// Presents one impact: a readable table for people, JSON for programs.
// Both carry SI values; object speeds also in ft/min and link rates in rpm, the
// units of report 445-1.
#include <nlohmann/json.hpp>
#include <string>

#include "blade/impact.hpp"
#include "scenario/impact_input.hpp"

namespace j232::report {

nlohmann::ordered_json impact_json(const scenario::ImpactCase& input, const blade::ImpactSolution& solution);
std::string impact_table(const scenario::ImpactCase& input, const blade::ImpactSolution& solution);

}  // namespace j232::report
