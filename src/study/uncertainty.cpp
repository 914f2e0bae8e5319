#include "study/uncertainty.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <stdexcept>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "scenario/input_error.hpp"
#include "scenario/toml_reader.hpp"
#include "study/parameters.hpp"
#include "scenario/scenario_reader.hpp"

namespace j232::study {

namespace {
using scenario::InputError;
using scenario::UncertainInput;

// A value written as a number and an optional unit ("0.7", "10 deg"): its parts.
struct Written {
  double number = 0;
  std::string unit;
};
Written split(const std::string& text, const std::string& file, std::optional<int> line, const std::string& key) {
  std::size_t used = 0;
  Written w;
  try {
    w.number = std::stod(text, &used);
  } catch (const std::exception&) {
    throw InputError(file, line, key, text, "expected a number, with a unit where the key takes one (\"0.7\", \"10 deg\")");
  }
  w.unit = text.substr(used);
  w.unit.erase(0, w.unit.find_first_not_of(' '));
  return w;
}
// "restitution = 0.62, crush_depth = 1.2": a draw's inputs, as numbers written in the
// inputs' units.
std::string draw_inputs(const UncertaintyPlan& plan, const std::vector<double>& values) {
  std::string out;
  for (std::size_t i = 0; i < plan.inputs.size() && i < values.size(); ++i) {
    const auto& choices = plan.inputs[i].values;
    if (!choices.empty())
      out += fmt::format("{}{} = {}", i ? ", " : "", plan.inputs[i].parameter, choices[std::min(choices.size() - 1, static_cast<std::size_t>(values[i]))]);
    else
      out += fmt::format("{}{} = {:.4g}", i ? ", " : "", plan.inputs[i].parameter, values[i]);
  }
  return out;
}

}  // namespace

double InputDistribution::quantile(double u) const {
  switch (kind) {
    case Kind::Uniform: return low + u * (high - low);
    case Kind::Triangular: {
      const double split = (mode - low) / (high - low);  // F(mode)
      return u < split ? low + std::sqrt(u * (high - low) * (mode - low)) : high - std::sqrt((1 - u) * (high - low) * (high - mode));
    }
    case Kind::Normal: {
      const boost::math::normal_distribution<double> n(0.5 * (low + high), sd);
      const double a = boost::math::cdf(n, low), b = boost::math::cdf(n, high);
      return std::clamp(boost::math::quantile(n, a + u * (b - a)), low, high);
    }
  }
  return low;
}

UncertaintyPlan uncertainty_plan(const scenario::Scenario& s) {
  UncertaintyPlan plan;
  plan.base_draws = static_cast<std::size_t>(s.uncertainty.base_draws);
  plan.replicates = s.uncertainty.replicates;
  if (!s.uncertainty.inputs.empty()) {
    plan.inputs = s.uncertainty.inputs;
    return plan;
  }
  // The estimated inputs (docs/model.md §8), each over a range with its basis.
  plan.defaults = true;
  auto estimated = [](std::string parameter, std::string low, std::string high, std::string basis) {
    scenario::UncertainInput in;
    in.parameter = std::move(parameter), in.low = std::move(low), in.high = std::move(high), in.basis = std::move(basis);
    return in;
  };
  plan.inputs = {
      estimated("board.puncture_energy_per_width", "80 J/m", "140 J/m",
                "estimate: no published value for 350# double-wall board; 110 J/m +/- ~27 %"),
      estimated("board.hit_fraction", "0.2", "0.4", "estimate: a hit takes about a third of a puncture's energy"),
      estimated("board.crush_depth", "3 mm", "12 mm", "estimate: about the board's caliper (7 mm); how deep a mark crushes it is not measured"),
      estimated(
          "restitution", "0.4", "0.95",
          "report 445-1: drop tests 0.9-0.96 at ~1 m/s, 0.45-0.6 at ~2.3 m/s; its Table 3.1 fits 0.53-0.65 at 11 m/s (j232 calibrate)"),
      estimated("bevel_angle", "20 deg", "45 deg", "estimate: mower blades are ground to about 30 deg; no figure for industrial cutters"),
      estimated("edge_friction", "0.2", "0.6", "handbook: steel on steel, kinetic 0.42-0.57; lower for an oily, worn edge"),
      estimated("ground.restitution", "0.1", "0.25", "estimate: rockfall field data give a normal e of about 0.2"),
      estimated("ground.max_restitution", "0.5", "0.95", "estimate: the angle law passes 1 at grazing impacts; a bounce off turf loses energy"),
      estimated("housing.friction", "0.3", "0.6", "handbook: steel on steel, kinetic 0.42-0.57"),
      estimated("feed.tilt_max", "0 deg", "10 deg", "estimate: SAE J232's feed tube geometry is not available"),
  };
  if (!s.housing.guards.empty())
    plan.inputs.push_back(estimated("housing.guards.openness", "0.1", "0.4", "estimate: single row 0.3-0.5 open, double row 0.1-0.25"));
  return plan;
}

UncertaintyResult run_uncertainty(const std::string& file, int threads, const std::function<void(std::size_t, std::size_t)>& on_run,
                                  const UncertaintyJournal* journal) {
  const toml::table base = scenario::parse_toml_file(file);
  const scenario::Scenario nominal = scenario::read_scenario(base, file);
  UncertaintyResult r;
  r.plan = uncertainty_plan(nominal);
  r.scenario_file = file;
  r.title = nominal.title;
  r.seed = nominal.run.seed;
  r.required = nominal.criteria.required_pass_probability;
  const std::size_t k = r.plan.inputs.size();
  // Each input's two ends, checked before anything runs.
  std::vector<ParameterInfo> info;
  std::vector<std::pair<Written, Written>> ends;
  std::vector<InputDistribution> spread;
  for (std::size_t i = 0; i < k; ++i) {
    const UncertainInput& in = r.plan.inputs[i];
    const std::string key = r.plan.defaults ? fmt::format("(default) {}", in.parameter) : fmt::format("uncertainty.inputs[{}]", i + 1);
    info.push_back(parameter_info(in.parameter));
    // A value the input may take must make a scenario the reader (and the parameter) accepts.
    const auto check_value = [&](const std::string& text, const std::string& where) {
      const Setting setting = make_setting(info.back(), text, file, in.line, where);
      toml::table doc = base;
      apply_to_document(setting, doc, file);
      auto sc = scenario::read_scenario(doc, file);
      try {
        apply(setting, sc);
      } catch (const std::invalid_argument& e) {
        throw InputError(file, in.line, where, text, e.what());
      }
    };
    if (!in.values.empty()) {
      // A discrete input: every value it may take must make a scenario the reader accepts.
      ends.emplace_back(Written{}, Written{});
      spread.push_back({});
      for (const std::string& text : in.values) check_value(text, key + ".values");
      continue;
    }
    const Written lo = split(in.low, file, in.line, key + ".low"), hi = split(in.high, file, in.line, key + ".high");
    if (lo.unit != hi.unit)
      throw InputError(file, in.line, key + ".high", in.high, fmt::format("expected the same unit as low (\"{}\")", lo.unit));
    if (!(hi.number > lo.number)) throw InputError(file, in.line, key + ".high", in.high, "expected a value above low");
    ends.emplace_back(lo, hi);
    InputDistribution d{InputDistribution::Kind::Uniform, lo.number, hi.number, 0.5 * (lo.number + hi.number),
                        0.25 * (hi.number - lo.number)};
    if (in.distribution == "triangular") d.kind = InputDistribution::Kind::Triangular;
    if (in.distribution == "normal") d.kind = InputDistribution::Kind::Normal;
    if (!in.mode.empty()) {
      const Written m = split(in.mode, file, in.line, key + ".mode");
      if (m.unit != lo.unit || !(m.number >= lo.number && m.number <= hi.number))
        throw InputError(file, in.line, key + ".mode", in.mode,
                         fmt::format("expected a value from low to high, in low's unit (\"{}\")", lo.unit));
      d.mode = m.number;
    }
    if (!in.sd.empty()) {
      const Written sd = split(in.sd, file, in.line, key + ".sd");
      if (sd.unit != lo.unit || !(sd.number > 0))
        throw InputError(file, in.line, key + ".sd", in.sd,
                         fmt::format("expected a standard deviation above zero, in low's unit (\"{}\")", lo.unit));
      d.sd = sd.number;
    }
    spread.push_back(d);
    // Both ends must make a scenario the reader accepts.
    for (const Written& w : {lo, hi})
      check_value(w.unit.empty() ? fmt::format("{:.17g}", w.number) : fmt::format("{:.17g} {}", w.number, w.unit), key);
  }
  r.design = saltelli_design(k, r.plan.base_draws);
  const auto runs = r.design.runs();
  for (std::size_t run = 0; run < runs.size(); ++run) {
    if (on_run) on_run(run, runs.size());
    toml::table doc = base;
    std::vector<Setting> settings;
    std::vector<double> values;
    for (std::size_t i = 0; i < k; ++i) {
      const auto& choices = r.plan.inputs[i].values;
      // A discrete input takes value floor(u n) of its n (recorded as that index); a range,
      // its distribution's quantile at u.
      const double v = choices.empty() ? spread[i].quantile(runs[run][i])
                                       : std::min(static_cast<double>(choices.size() - 1), std::floor(runs[run][i] * static_cast<double>(choices.size())));
      const std::string text = !choices.empty()              ? choices[static_cast<std::size_t>(v)]
                               : ends[i].first.unit.empty() ? fmt::format("{:.17g}", v)
                                                            : fmt::format("{:.17g} {}", v, ends[i].first.unit);
      settings.push_back(make_setting(info[i], text, file, r.plan.inputs[i].line, r.plan.inputs[i].parameter));
      values.push_back(v);
      apply_to_document(settings.back(), doc, file);
    }
    r.values.push_back(values);
    if (journal && journal->recall)
      if (const auto kept = journal->recall(run)) {
        r.runs.push_back(*kept);
        r.outputs.push_back(kept->outputs);
        continue;
      }
    scenario::Scenario sc = scenario::read_scenario(doc, file);
    for (const auto& st : settings) apply(st, sc);
    sc.run.replicates = r.plan.replicates;  // common random numbers: the same seed and replicates at every draw
    sc.run.target_half_width.reset();
    sc.run.until_settled = false;
    const assess::Simulator sim(sc);
    const auto a = assess::run_assessment(sim, threads);
    const auto sum = assess::summarise(a, sc);
    if (!sum.validity.valid)
      throw InputError(file, std::nullopt, "uncertainty", fmt::format("draw {} ({})", run + 1, draw_inputs(r.plan, values)),
                       "the simulated test is invalid at this draw: " + sum.validity.reasons.front());
    // (From every nail where it can be computed; else, for the `marks` denominator, the
    // replicates' share, as uq.json says.)
    UqRun out;
    out.outputs = {sum.pass.estimate, sum.exact.computed ? sum.exact.value : sum.pass.estimate, sum.criteria[0].mean_share,
                   sum.criteria[1].mean_share, sum.criteria[2].mean_share, sum.criteria[3].mean_share,
                   (sum.exact.computed ? sum.exact.value : sum.pass.estimate) >= r.required ? 1.0 : 0.0};
    const auto cut = sum.fates[static_cast<std::size_t>(flight::Fate::CutOff)];
    out.cut_off_share = sum.struck ? static_cast<double>(cut) / static_cast<double>(sum.struck) : 0.0;
    for (int why = 1; why < flight::kCutOffReasons; ++why)
      if (sum.cut_off_by[static_cast<std::size_t>(why)] > sum.cut_off_by[static_cast<std::size_t>(out.cut_off_limit)]) out.cut_off_limit = why;
    r.runs.push_back(out);
    r.outputs.push_back(out.outputs);
    if (journal && journal->record) journal->record(run, out);
  }
  for (std::size_t run = 0; run < r.runs.size(); ++run)
    if (r.runs[run].cut_off_share >= assess::kWarnCutOffShare) {
      const std::string inputs = draw_inputs(r.plan, r.values[run]);
      r.warnings.push_back(fmt::format(
          "draw {} ({}): {:.2f} % of struck nails were cut off still moving, mostly by {}, nearing the {:g} % at which a run is "
          "invalid",
          run + 1, inputs, 100 * r.runs[run].cut_off_share, flight::cut_off_name(static_cast<flight::CutOff>(r.runs[run].cut_off_limit)),
          100 * assess::kMaxCutOffShare));
    }
  for (int o = 0; o < kUqOutputs; ++o) {
    std::vector<double> f;
    for (const auto& out : r.outputs) f.push_back(out[static_cast<std::size_t>(o)]);
    r.indices[static_cast<std::size_t>(o)] = sobol_indices(r.design, f, 500, 1);
  }
  if (r.design.base >= 4) {
    r.half_indices.emplace();
    for (int o = 0; o < kUqOutputs; ++o) {
      std::vector<double> f;
      for (const auto& out : r.outputs) f.push_back(out[static_cast<std::size_t>(o)]);
      (*r.half_indices)[static_cast<std::size_t>(o)] = sobol_indices_prefix(r.design, f, r.design.base / 2, 500, 1);
    }
  }
  return r;
}

}  // namespace j232::study
