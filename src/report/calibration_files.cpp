#include "report/calibration_files.hpp"

#include <fmt/format.h>

#include <cmath>

#include "report/text_safety.hpp"

namespace j232::report {

namespace {
constexpr double kFtPerMin = 0.00508;  // m/s

double percent(double predicted, double measured) { return 100 * (predicted / measured - 1); }
const char* law_name(study::LawKind k) { return k == study::LawKind::Constant ? "constant" : "power_law"; }
}  // namespace

std::string calibration_table(const study::CalibrationResult& r) {
  std::string o =
      fmt::format("Restitution law fitted to {} cases of {}:\n  {}\n", r.cases.size(), terminal_safe(r.cases_file), r.fitted.describe());
  for (const auto& p : r.parameters)
    o += fmt::format("  {:<12} {:.4g}  (95 % interval {:.4g} to {:.4g}; standard error {:.2g}, {} degrees of freedom)\n", p.name, p.value,
                     p.low, p.high, p.standard_error, r.degrees_of_freedom);
  o += fmt::format("\n{:<36} {:>10} {:>18} {:>18} {:>18} {:>6}\n", "case", "measured", "as given", "fitted", "held out", "e");
  o += fmt::format("{:<36} {:>10} {:>18} {:>18} {:>18} {:>6}\n", "", "ft/min", "ft/min (error)", "ft/min (error)", "ft/min (error)",
                   "fitted");
  for (const auto& k : r.cases) {
    auto cell = [&](double v) { return fmt::format("{:.0f} ({:+.1f} %)", v / kFtPerMin, percent(v, k.measured)); };
    o += fmt::format("{:<36} {:>10.0f} {:>18} {:>18} {:>18} {:>6.3f}\n", terminal_safe(k.name).substr(0, 36), k.measured / kFtPerMin,
                     cell(k.as_given), cell(k.fitted), cell(k.held_out), k.e_fitted);
  }
  o += fmt::format("\nRMS error: {:.1f} % as given, {:.1f} % fitted, {:.1f} % held out (each case predicted by a fit to the others)\n",
                   100 * r.rms_as_given, 100 * r.rms_fitted, 100 * r.rms_held_out);
  return o;
}

nlohmann::ordered_json calibration_json(const study::CalibrationResult& r) {
  nlohmann::ordered_json j;
  j["cases_file"] = r.cases_file;
  j["law"] = law_name(r.law);
  j["fitted"] = r.fitted.describe();
  if (r.law == study::LawKind::PowerLaw) {
    j["reference_speed_m_s"] = r.fitted.reference_speed;
    j["maximum"] = r.fitted.maximum;
  }
  j["fit"] = "least squares on ln(predicted / measured speed); 95 % intervals from the covariance s^2 (J'J)^-1 and Student's t";
  j["degrees_of_freedom"] = r.degrees_of_freedom;
  for (const auto& p : r.parameters)
    j["parameters"].push_back(
        {{"name", p.name}, {"value", p.value}, {"standard_error", p.standard_error}, {"low", p.low}, {"high", p.high}});
  for (const auto& k : r.cases)
    j["cases"].push_back({{"case", k.name},
                          {"approach_speed_m_s", k.approach_speed},
                          {"measured_m_s", k.measured},
                          {"as_given_m_s", k.as_given},
                          {"fitted_m_s", k.fitted},
                          {"held_out_m_s", k.held_out},
                          {"e_fitted", k.e_fitted},
                          {"error_as_given", k.as_given / k.measured - 1},
                          {"error_fitted", k.fitted / k.measured - 1},
                          {"error_held_out", k.held_out / k.measured - 1}});
  j["rms_error"] = {{"as_given", r.rms_as_given}, {"fitted", r.rms_fitted}, {"held_out", r.rms_held_out}};
  return j;
}

std::string calibration_csv(const study::CalibrationResult& r) {
  std::string o = "case,approach_speed_m_s,measured_m_s,as_given_m_s,fitted_m_s,held_out_m_s,e_fitted\n";
  for (const auto& k : r.cases)
    o += fmt::format("{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", csv_text_cell(k.name), k.approach_speed, k.measured, k.as_given,
                     k.fitted, k.held_out, k.e_fitted);
  return o;
}

std::string calibration_toml(const study::CalibrationResult& r) {
  std::string o = fmt::format("# Fitted by `j232 calibrate` to {} ({} cases): RMS error {:.1f} % fitted, {:.1f} % held out.\n",
                              r.cases_file, r.cases.size(), 100 * r.rms_fitted, 100 * r.rms_held_out);
  const auto& first = r.parameters.front();
  const std::string basis = fmt::format("fitted to {}: 95 % interval of {}", r.cases_file, first.name);
  if (r.law == study::LawKind::Constant) {
    o += fmt::format("[restitution]\ne = {:.4f}\n\n", r.fitted.e);
    o += fmt::format("[[uncertainty.inputs]]\nparameter = \"restitution\"\nlow = \"{:.4f}\"\nhigh = \"{:.4f}\"\nbasis = \"{}\"\n",
                     std::max(0.0, first.low), std::min(1.0, first.high), basis);
  } else {
    o += fmt::format(
        "[restitution]\nmodel = \"power_law\"\ncoefficient = {:.4f}\nexponent = {:.4f}\nmaximum = {:.4f}\nreference_speed = \"{:.4g} "
        "m/s\"\n\n",
        r.fitted.coefficient, r.fitted.exponent, r.fitted.maximum, r.fitted.reference_speed);
    o += fmt::format(
        "[[uncertainty.inputs]]\nparameter = \"restitution.coefficient\"\nlow = \"{:.4f}\"\nhigh = \"{:.4f}\"\nbasis = \"{}\"\n",
        std::max(1e-6, first.low), first.high, basis);
  }
  return o;
}

std::string drop_test_table(const std::vector<study::DropTest>& drops, const study::DropTestResult& r) {
  std::string o = fmt::format("{:>5} {:>12} {:>14} {:>14} {:>7}\n", "drop", "height (m)", "rebound (m)", "impact (m/s)", "e");
  for (std::size_t i = 0; i < drops.size(); ++i)
    o += fmt::format("{:>5} {:>12.4g} {:>14.4g} {:>14.3g} {:>7.4f}\n", i + 1, drops[i].drop_height, drops[i].rebound_height,
                     r.impact_speed[i], r.e[i]);
  o +=
      fmt::format("\ne = sqrt(rebound / drop height): mean {:.4f}, standard deviation {:.4f}, 95 % interval of the mean {:.4f} to {:.4f}\n",
                  r.mean, r.standard_deviation, r.low, r.high);
  return o;
}

nlohmann::ordered_json drop_test_json(const std::vector<study::DropTest>& drops, const study::DropTestResult& r) {
  nlohmann::ordered_json j;
  j["method"] = "e = sqrt(rebound height / drop height), at the impact speed sqrt(2 g h)";
  for (std::size_t i = 0; i < drops.size(); ++i)
    j["drops"].push_back({{"drop_height_m", drops[i].drop_height},
                          {"rebound_height_m", drops[i].rebound_height},
                          {"impact_speed_m_s", r.impact_speed[i]},
                          {"e", r.e[i]}});
  j["e"] = {{"mean", r.mean}, {"standard_deviation", r.standard_deviation}, {"low", r.low}, {"high", r.high}};
  return j;
}

}  // namespace j232::report
