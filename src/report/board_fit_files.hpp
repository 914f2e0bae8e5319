#pragma once
// What `j232 calibrate --board` writes: the fitted board on the terminal, board.toml (the
// [board] values and the [[uncertainty.inputs]] ranges for a scenario) and
// calibrate-board.json (every number, and each drop's E/w and fitted probabilities).
#include <nlohmann/json.hpp>
#include <string>
#include "study/board_calibration.hpp"

namespace j232::report {
std::string board_fit_text(const study::BoardFit& f);
std::string board_fit_toml(const study::BoardFit& f);
nlohmann::ordered_json board_fit_json(const study::BoardFit& f, const std::vector<study::BoardDrop>& drops);
}  // namespace j232::report
