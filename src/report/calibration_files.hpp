#pragma once
// What `j232 calibrate` prints and writes: the fitted restitution law with its intervals,
// each case measured, as given, fitted and held out (calibrate.json, calibrate.csv), and
// the law as scenario text to paste (restitution.toml). Drop tests likewise.
#include <nlohmann/json.hpp>
#include <string>

#include "study/calibration.hpp"

namespace j232::report {

std::string calibration_table(const study::CalibrationResult& r);
nlohmann::ordered_json calibration_json(const study::CalibrationResult& r);
std::string calibration_csv(const study::CalibrationResult& r);
// A [restitution] table with the fitted law and an [[uncertainty.inputs]] entry spanning
// its 95 % interval (with its basis), for scenarios and `j232 uq`.
std::string calibration_toml(const study::CalibrationResult& r);

std::string drop_test_table(const std::vector<study::DropTest>& drops, const study::DropTestResult& r);
nlohmann::ordered_json drop_test_json(const std::vector<study::DropTest>& drops, const study::DropTestResult& r);

}  // namespace j232::report
