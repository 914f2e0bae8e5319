#pragma once
// The scenario as run, every default filled in, SI with the unit in each key's name;
// and the assumptions a report must name, each with its source.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scenario/scenario.hpp"

namespace j232::report {

nlohmann::ordered_json scenario_json(const scenario::Scenario& s);

struct Assumption {
  std::string what;
  std::string source;
};
std::vector<Assumption> assumptions(const scenario::Scenario& s);

}  // namespace j232::report
