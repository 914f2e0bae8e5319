#include "study/uncertainty.hpp"

#include <fmt/format.h>
#include <stdexcept>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "scenario/input_error.hpp"
#include "scenario/toml_reader.hpp"
#include "study/parameters.hpp"

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
}  // namespace

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
  plan.inputs = {
      {"board.puncture_energy_per_width", "80 J/m", "140 J/m", "estimate: no published value for 350# double-wall board; 110 J/m +/- ~27 %", {}},
      {"board.hit_fraction", "0.2", "0.4", "estimate: a hit takes about a third of a puncture's energy", {}},
      {"restitution", "0.7", "0.95", "report 445-1 measured 0.90-0.92 at ~1 m/s; lower at blade speeds", {}},
      {"lift_angle", "0 deg", "10 deg", "estimate: no figure for industrial cutters (flat bar 0 deg to a bevelled, sailed edge)", {}},
      {"ground.restitution", "0.1", "0.25", "estimate: rockfall field data give a normal e of about 0.2", {}},
      {"housing.friction", "0.3", "0.6", "handbook: steel on steel, kinetic 0.42-0.57", {}},
      {"feed.tilt_max", "0 deg", "10 deg", "estimate: SAE J232's feed tube geometry is not available", {}},
  };
  if (!s.housing.guards.empty())
    plan.inputs.push_back({"housing.guards.openness", "0.1", "0.4", "estimate: single row 0.3-0.5 open, double row 0.1-0.25", {}});
  return plan;
}

UncertaintyResult run_uncertainty(const std::string& file, int threads, const std::function<void(std::size_t, std::size_t)>& on_run) {
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
  for (std::size_t i = 0; i < k; ++i) {
    const UncertainInput& in = r.plan.inputs[i];
    const std::string key = r.plan.defaults ? fmt::format("(default) {}", in.parameter) : fmt::format("uncertainty.inputs[{}]", i + 1);
    info.push_back(parameter_info(in.parameter));
    const Written lo = split(in.low, file, in.line, key + ".low"), hi = split(in.high, file, in.line, key + ".high");
    if (lo.unit != hi.unit) throw InputError(file, in.line, key + ".high", in.high, fmt::format("expected the same unit as low (\"{}\")", lo.unit));
    if (!(hi.number > lo.number)) throw InputError(file, in.line, key + ".high", in.high, "expected a value above low");
    ends.emplace_back(lo, hi);
    // Both ends must make a scenario the reader accepts.
    for (const Written& w : {lo, hi}) {
      const std::string text = w.unit.empty() ? fmt::format("{:.17g}", w.number) : fmt::format("{:.17g} {}", w.number, w.unit);
      const Setting setting = make_setting(info.back(), text, file, in.line, key);
      toml::table doc = base;
      apply_to_document(setting, doc, file);
      auto sc = scenario::read_scenario(doc, file);
      try {
        apply(setting, sc);
      } catch (const std::invalid_argument& e) {
        throw InputError(file, in.line, key, text, e.what());
      }
    }
  }
  r.design = saltelli_design(k, r.plan.base_draws);
  const auto runs = r.design.runs();
  for (std::size_t run = 0; run < runs.size(); ++run) {
    if (on_run) on_run(run, runs.size());
    toml::table doc = base;
    std::vector<Setting> settings;
    std::vector<double> values;
    for (std::size_t i = 0; i < k; ++i) {
      const double v = ends[i].first.number + runs[run][i] * (ends[i].second.number - ends[i].first.number);
      const std::string text = ends[i].first.unit.empty() ? fmt::format("{:.17g}", v) : fmt::format("{:.17g} {}", v, ends[i].first.unit);
      settings.push_back(make_setting(info[i], text, file, r.plan.inputs[i].line, r.plan.inputs[i].parameter));
      values.push_back(v);
      apply_to_document(settings.back(), doc, file);
    }
    scenario::Scenario sc = scenario::read_scenario(doc, file);
    for (const auto& st : settings) apply(st, sc);
    sc.run.replicates = r.plan.replicates;  // common random numbers: the same seed and replicates at every draw
    sc.run.target_half_width.reset();
    const assess::Simulator sim(sc);
    const auto a = assess::run_assessment(sim, threads);
    const auto sum = assess::summarise(a, sc);
    if (!sum.validity.valid)
      throw InputError(file, std::nullopt, "uncertainty", fmt::format("draw {}", run + 1),
                       "the simulated test is invalid at this draw: " + sum.validity.reasons.front());
    r.values.push_back(values);
    r.outputs.push_back({sum.pass.estimate, sum.criteria[0].mean_share, sum.criteria[1].mean_share, sum.criteria[2].mean_share,
                         sum.criteria[3].mean_share, sum.pass.estimate >= r.required ? 1.0 : 0.0});
  }
  for (int o = 0; o < kUqOutputs; ++o) {
    std::vector<double> f;
    for (const auto& out : r.outputs) f.push_back(out[static_cast<std::size_t>(o)]);
    r.indices[static_cast<std::size_t>(o)] = sobol_indices(r.design, f, 500, 1);
  }
  return r;
}

}  // namespace j232::study
