#include "report/board_fit_files.hpp"

#include <fmt/format.h>

#include "report/text_safety.hpp"

namespace j232::report {

using json = nlohmann::ordered_json;

namespace {
const char* mark_name(board::Mark m) { return m == board::Mark::Puncture ? "puncture" : m == board::Mark::Hit ? "hit" : "none"; }
std::string depth_words(const study::BoardFit& f) {
  return f.crush_depth_determined
             ? fmt::format("{:.1f} mm (95 %: {:.1f} to {:.1f} mm, profile likelihood)", 1000 * f.crush_depth.value, 1000 * f.crush_depth.low,
                           1000 * f.crush_depth.high)
             : fmt::format("not determined by these drops (every depth from {:.1f} to {:.1f} mm fits them about as well: drop at "
                           "more angles between point first and flat); {:.1f} mm fits best",
                           1000 * f.crush_depth.low, 1000 * f.crush_depth.high, 1000 * f.crush_depth.value);
}
}  // namespace

std::string board_fit_text(const study::BoardFit& f) {
  std::string o = fmt::format("Board fitted to {} drops ({}): {} punctures, {} hits, {} without a mark\n", f.drops,
                              terminal_safe(f.drops_file), f.punctures, f.hits, f.drops - f.punctures - f.hits);
  o += fmt::format("  puncture energy per width k_p  {:.1f} J/m  ({}, bootstrap of the drops, the depth refitted in each)\n",
                   f.puncture_energy_per_width.value,
                   f.puncture_energy_per_width.bounded
                       ? fmt::format("95 %: {:.1f} to {:.1f}", f.puncture_energy_per_width.low, f.puncture_energy_per_width.high)
                       : "no interval: too few drops on one side of the threshold for resampling to bracket it");
  if (f.hit_fraction_determined)
    o += fmt::format("  hit fraction f_h               {:.3f}     ({})\n", f.hit_fraction.value,
                     f.hit_fraction.bounded ? fmt::format("95 %: {:.3f} to {:.3f}", f.hit_fraction.low, f.hit_fraction.high)
                                            : "no interval: too few drops on one side of the hit threshold");
  else
    o += "  hit fraction f_h               not determined: it needs drops that left a hit and drops that left no mark\n";
  o += fmt::format("  crush depth delta              {}\n", depth_words(f));
  o += fmt::format("  scatter of the threshold       sigma {:.3f} of ln(E/w) (95 %: {:.3f} to {:.3f}): one spot's threshold within a "
                   "factor {:.2f} of the model's for two in three drops\n",
                   f.scatter.value, f.scatter.low, f.scatter.high, std::exp(f.scatter.value));
  if (f.separated)
    o += "  NOTE: a threshold separates these drops perfectly, so they cannot say how far the board scatters: sigma and the "
         "intervals rest on the prior on sigma (median 0.1). Drops near the thresholds would pin them down.\n";
  o += "  (the simulation's board has no scatter: it takes the fitted thresholds; the intervals belong in j232 uq's ranges)\n";
  return o;
}

std::string board_fit_toml(const study::BoardFit& f) {
  std::string o = fmt::format("# The board fitted by `j232 calibrate --board` to {} drops ({}).\n", f.drops, f.drops_file);
  o += "[board]\n";
  o += fmt::format("puncture_energy_per_width = \"{:.4g} J/m\"\n", f.puncture_energy_per_width.value);
  if (f.hit_fraction_determined) o += fmt::format("hit_fraction = {:.4g}\n", f.hit_fraction.value);
  if (f.crush_depth_determined) o += fmt::format("crush_depth = \"{:.3g} mm\"\n", 1000 * f.crush_depth.value);
  o += "\n# Their 95 % intervals, for j232 uq (add to the scenario's [uncertainty] table). k_p and the crush depth are\n"
       "# linked (a deeper crush presses a wider nail): drawn independently, their ranges overstate the spread.\n";
  if (f.puncture_energy_per_width.bounded)
    o += fmt::format(
      "[[uncertainty.inputs]]\nparameter = \"board.puncture_energy_per_width\"\nlow = \"{:.4g} J/m\"\nhigh = \"{:.4g} J/m\"\nbasis = \"j232 "
      "calibrate --board {}: 95 % bootstrap interval\"\n",
      f.puncture_energy_per_width.low, f.puncture_energy_per_width.high, f.drops_file);
  if (f.hit_fraction_determined && f.hit_fraction.bounded && f.hit_fraction.high > f.hit_fraction.low)
    o += fmt::format(
        "\n[[uncertainty.inputs]]\nparameter = \"board.hit_fraction\"\nlow = {:.4g}\nhigh = {:.4g}\nbasis = \"j232 calibrate --board {}: 95 % "
        "bootstrap interval\"\n",
        f.hit_fraction.low, f.hit_fraction.high, f.drops_file);
  if (f.crush_depth_determined && f.crush_depth.high > f.crush_depth.low)
    o += fmt::format(
        "\n[[uncertainty.inputs]]\nparameter = \"board.crush_depth\"\nlow = \"{:.3g} mm\"\nhigh = \"{:.3g} mm\"\nbasis = \"j232 calibrate --board "
        "{}: 95 % profile-likelihood interval\"\n",
        1000 * f.crush_depth.low, 1000 * f.crush_depth.high, f.drops_file);
  return o;
}

json board_fit_json(const study::BoardFit& f, const std::vector<study::BoardDrop>& drops) {
  const auto estimate = [](const study::Estimate& e, double scale = 1.0) {
    return json{{"value", e.value * scale}, {"low", e.bounded ? json(e.low * scale) : json(nullptr)}, {"high", e.bounded ? json(e.high * scale) : json(nullptr)}};
  };
  json rows = json::array();
  for (std::size_t i = 0; i < drops.size(); ++i)
    rows.push_back({{"line", drops[i].line},
                    {"speed_m_s", drops[i].speed},
                    {"axis_angle_deg", drops[i].axis_angle * 180 / M_PI},
                    {"spin_rad_s", drops[i].spin},
                    {"result", mark_name(drops[i].result)},
                    {"energy_per_width_J_m", f.energy_per_width[i]},
                    {"p_mark", f.p_mark[i]},
                    {"p_puncture", f.p_puncture[i]}});
  return {{"program", "j232 calibrate --board"},
          {"drops_file", f.drops_file},
          {"model",
           "ordered probit in ln(E/w): P(puncture) = Phi((ln(E/w) - ln k_p)/sigma), P(mark) = Phi((ln(E/w) - ln(f_h k_p))/sigma); E and "
           "w as the flight computes them at the board; k_p, f_h, sigma by maximum a posteriori (a weak prior on sigma) at each crush "
           "depth of a 1-15 mm grid, the depth by its profile"},
          {"drops", f.drops},
          {"punctures", f.punctures},
          {"hits", f.hits},
          {"puncture_energy_per_width_J_m", estimate(f.puncture_energy_per_width)},
          {"hit_fraction", f.hit_fraction_determined ? estimate(f.hit_fraction) : json(nullptr)},
          {"crush_depth_mm", estimate(f.crush_depth, 1000)},
          {"crush_depth_determined", f.crush_depth_determined},
          {"scatter_sigma", estimate(f.scatter)},
          {"scatter_prior", "ln sigma ~ N(ln 0.1, 1), an estimate: it keeps perfectly separated drops from collapsing sigma"},
          {"perfectly_separated", f.separated},
          {"log_posterior", f.log_posterior},
          {"bootstrap_draws", f.bootstrap_draws},
          {"per_drop", rows}};
}

}  // namespace j232::report
