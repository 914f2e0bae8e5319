#pragma once
// Fitting the nail-on-blade restitution law to measurements (docs/model.md §6c): impact
// cases with measured discharge speeds (report 445-1's Table 3.1 ships as the example), a
// law's parameters fitted by least squares on the log of predicted over measured speed,
// with 95 % intervals, and every case predicted by a fit to the others (leave-one-out), so
// the reader sees how well the fitted law predicts a case it has not seen. And the report's
// own way to measure e: drop tests, e = sqrt(rebound height / drop height).
#include <string>
#include <vector>

#include "blade/restitution.hpp"
#include "scenario/impact_input.hpp"

namespace j232::study {

// One measured impact: an impact case (a file of scenarios/impact/ with keys set over it)
// and the object's measured speed after the impact.
struct CalibrationCase {
  std::string name;
  scenario::ImpactCase input;
  double measured_speed = 0.0;  // m/s
  int line = 0;                 // in the cases file
};

// Reads a cases file: CSV with columns `case` (a name), `scenario` (an impact case file,
// relative to the CSV's folder), `measured_speed` (with its unit, "2615 ft/min"), and any
// other column a scenario key set over the file for that row ("object.mass" = "19 g").
// Throws InputError naming the file, line and column.
std::vector<CalibrationCase> read_calibration_cases(const std::string& csv_file);

enum class LawKind { Constant, PowerLaw };

struct FittedParameter {
  std::string name;                                         // "e", or "coefficient" and "exponent"
  double value = 0, standard_error = 0, low = 0, high = 0;  // 95 % interval
};

struct CasePrediction {
  std::string name;
  double measured = 0;        // m/s
  double approach_speed = 0;  // normal approach speed at the contact, m/s
  double as_given = 0;        // with the case's own restitution
  double fitted = 0;          // with the law fitted to all cases
  double held_out = 0;        // with the law fitted to all other cases
  double e_fitted = 0;        // the fitted law's e at this case
};

struct CalibrationResult {
  std::string cases_file;
  LawKind law = LawKind::Constant;
  blade::Restitution fitted;
  std::vector<FittedParameter> parameters;
  std::vector<CasePrediction> cases;
  int degrees_of_freedom = 0;
  // Root mean square of predicted / measured - 1: as given, fitted, held out.
  double rms_as_given = 0, rms_fitted = 0, rms_held_out = 0;
};

// Fits the law to the cases. Throws InputError when the cases cannot determine it (fewer
// cases than parameters plus one; approach speeds too alike to fit a speed dependence).
CalibrationResult calibrate(const std::vector<CalibrationCase>& cases, LawKind law, const std::string& cases_file);

// Drop tests: a ball of the object's material dropped from h0 rebounds to h1 off the
// blade's steel; e = sqrt(h1 / h0) at the impact speed sqrt(2 g h0).
struct DropTest {
  double drop_height = 0, rebound_height = 0;  // m
  int line = 0;
};
struct DropTestResult {
  std::vector<double> e, impact_speed;                         // per drop
  double mean = 0, standard_deviation = 0, low = 0, high = 0;  // 95 % interval of the mean
};
// Reads a CSV with columns drop_height and rebound_height (with units). Throws InputError.
std::vector<DropTest> read_drop_tests(const std::string& csv_file);
DropTestResult restitution_from_drops(const std::vector<DropTest>& drops);

}  // namespace j232::study
