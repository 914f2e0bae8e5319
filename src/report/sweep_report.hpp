#pragma once
// What `j232 sweep` writes for a finished sweep: its table as CSV and its charts.
#include <string>
#include <utility>
#include <vector>

#include "study/sweep.hpp"

namespace j232::report {

std::string sweep_csv(const study::SweepSpec& spec, const study::SweepTable& t);
// The charts: for impact cases "dimensional" and "dimensionless"; for J232 scenarios
// "pass-probability" and one per criterion's share. Each as (suffix, svg).
std::vector<std::pair<std::string, std::string>> sweep_charts(const study::SweepSpec& spec, const study::SweepTable& t);

}  // namespace j232::report
