#include "study/uncertainty.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "assess/summary.hpp"  // kWarnCutOffShare
#include "pipeline/pipeline.hpp"
#include "scenario/input_error.hpp"
#include "scenario/toml_reader.hpp"
#include "study/parameters.hpp"
#include "scenario/scenario_reader.hpp"

namespace j232::study {

namespace {
// The origin a drawn value carries into the scenario's reader, so an error about it names
// the study input that drew it ("file:line (uncertainty.inputs[2])"), not the scenario's key.
std::string drawn_by(const std::string& file, const scenario::UncertainInput& in, const std::string& input) {
  return in.line ? fmt::format("{}:{} ({})", file, *in.line, input) : fmt::format("{} ({})", file, input);
}

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
// Why a key cannot be an uncertain input of a study (empty: it can).
std::string cannot_vary(const std::string& key, const pipeline::Pipeline& pipeline) {
  if (key == "run.seed")
    return "every draw runs with the scenario's seed (common random numbers, so that draws differ by their inputs, not by noise); "
           "a seed drawn would undo that";
  if (key == "run.replicates") return "each assessment runs [uncertainty] replicates; set that instead";
  if (key == "field.objects_simulated") return "each assessment simulates [uncertainty] objects; set that instead";
  if (key.rfind("field.planes", 0) == 0 && !(key.size() >= 9 && key.compare(key.size() - 9, 9, ".distance") == 0))
    return "a plane's side, receptor and name decide which figures the study judges; only its distance can be drawn";
  return pipeline.cannot_vary(key);
}

}  // namespace

// "restitution = 0.62, crush_depth = 1.2 mm": a draw's inputs, as numbers with the units
// their ranges were written in.
std::string draw_inputs(const UncertaintyPlan& plan, const std::vector<double>& values) {
  std::string out;
  for (std::size_t i = 0; i < plan.inputs.size() && i < values.size(); ++i) {
    const auto& choices = plan.inputs[i].values;
    if (!choices.empty()) {
      out += fmt::format("{}{} = {}", i ? ", " : "", plan.inputs[i].parameter, choices[std::min(choices.size() - 1, static_cast<std::size_t>(values[i]))]);
    } else {
      std::string unit;
      try {
        unit = split(plan.inputs[i].low, "", std::nullopt, plan.inputs[i].parameter).unit;
      } catch (const InputError&) {
        // (the plan was checked when read: never here)
      }
      out += fmt::format("{}{} = {:.4g}{}{}", i ? ", " : "", plan.inputs[i].parameter, values[i], unit.empty() ? "" : " ", unit);
    }
  }
  return out;
}


std::vector<UqOutput> uq_outputs(const scenario::Scenario& s) { return pipeline::pipeline_of(s).outputs(s); }

double InputDistribution::quantile(double u) const {
  switch (kind) {
    case Kind::Uniform: return low + u * (high - low);
    case Kind::Triangular: {
      const double split = (mode - low) / (high - low);  // F(mode)
      return u < split ? low + std::sqrt(u * (high - low) * (mode - low)) : high - std::sqrt((1 - u) * (high - low) * (high - mode));
    }
    case Kind::LogUniform: return low * std::pow(high / low, u);
    case Kind::Normal: {
      const boost::math::normal_distribution<double> n(0.5 * (low + high), sd);
      const double a = boost::math::cdf(n, low), b = boost::math::cdf(n, high);
      return std::clamp(boost::math::quantile(n, a + u * (b - a)), low, high);
    }
  }
  return low;
}

scenario::Scenario scenario_with(const toml::table& base, const std::string& file, const UncertainInput& in, const std::string& text,
                                 const std::string& where) {
  const Setting setting = make_setting(parameter_info(in.parameter), text, file, in.line, where);
  toml::table doc = base;
  apply_to_document(setting, doc, drawn_by(file, in, where));
  auto sc = scenario::read_scenario(doc, file);
  try {
    apply(setting, sc);
  } catch (const std::invalid_argument& e) {
    throw InputError(file, in.line, where, text, e.what());
  }
  return sc;
}

UncertaintyPlan uncertainty_plan(const scenario::Scenario& s) {
  const pipeline::Pipeline& pipeline = pipeline::pipeline_of(s);
  UncertaintyPlan plan;
  plan.base_draws = static_cast<std::size_t>(s.uncertainty.base_draws);
  const pipeline::DrawSize size = pipeline.draw_size(s);
  plan.replicates = size.replicates, plan.objects = size.objects;
  plan.defaults = s.uncertainty.inputs.empty();
  plan.inputs = plan.defaults ? pipeline.estimated_inputs(s) : s.uncertainty.inputs;
  return plan;
}

namespace {

// Each input's two ends (or its values) and its distribution, checked before anything runs:
// every value it may take must make a scenario the reader and the parameter accept.
struct InputSpreads {
  std::vector<ParameterInfo> info;
  std::vector<std::pair<Written, Written>> ends;  // a range's (a discrete input's: empty)
  std::vector<InputDistribution> spread;
};

InputSpreads read_spreads(const toml::table& base, const std::string& file, const pipeline::Pipeline& pipeline, const UncertaintyResult& r) {
  const std::size_t k = r.plan.inputs.size();
  InputSpreads spreads;
  for (std::size_t i = 0; i < k; ++i) {
    const UncertainInput& in = r.plan.inputs[i];
    const std::string key = r.plan.defaults ? fmt::format("(default) {}", in.parameter) : fmt::format("uncertainty.inputs[{}]", i + 1);
    spreads.info.push_back(parameter_info(in.parameter));
    if (const std::string why = cannot_vary(in.parameter, pipeline); !why.empty())
      throw InputError(file, in.line, r.plan.defaults ? key : key + ".parameter", in.parameter, why);
    // A value the input may take must make a scenario the reader (and the parameter) accepts.
    const auto check_value = [&](const std::string& text, const std::string& where) { scenario_with(base, file, in, text, where); };
    if (!in.values.empty()) {
      // A discrete input: every value it may take must make a scenario the reader accepts.
      spreads.ends.emplace_back(Written{}, Written{});
      spreads.spread.push_back({});
      for (const std::string& text : in.values) check_value(text, key + ".values");
      continue;
    }
    const Written lo = split(in.low, file, in.line, key + ".low"), hi = split(in.high, file, in.line, key + ".high");
    if (lo.unit != hi.unit)
      throw InputError(file, in.line, key + ".high", in.high, fmt::format("expected the same unit as low (\"{}\")", lo.unit));
    if (!(hi.number > lo.number)) throw InputError(file, in.line, key + ".high", in.high, "expected a value above low");
    spreads.ends.emplace_back(lo, hi);
    InputDistribution d{InputDistribution::Kind::Uniform, lo.number, hi.number, 0.5 * (lo.number + hi.number),
                        0.25 * (hi.number - lo.number)};
    if (in.distribution == "triangular") d.kind = InputDistribution::Kind::Triangular;
    if (in.distribution == "normal") d.kind = InputDistribution::Kind::Normal;
    if (in.distribution == "loguniform") {
      if (!(lo.number > 0)) throw InputError(file, in.line, key + ".low", in.low, "expected a value above zero: a loguniform range spans a ratio");
      d.kind = InputDistribution::Kind::LogUniform;
    }
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
    spreads.spread.push_back(d);
    // Both ends must make a scenario the reader accepts.
    for (const Written& w : {lo, hi})
      check_value(w.unit.empty() ? fmt::format("{:.17g}", w.number) : fmt::format("{:.17g} {}", w.number, w.unit), key);
  }
  return spreads;
}

// Every draw of the Saltelli design: the scenario with the drawn inputs written in, read and
// assessed (or recalled from the journal of an interrupted study), its outputs recorded.
void run_draws(const toml::table& base, const std::string& file, const scenario::Scenario& nominal, const pipeline::Pipeline& pipeline,
               const InputSpreads& spreads, int threads,
               const std::function<void(std::size_t, std::size_t)>& on_run, const UncertaintyJournal* journal, UncertaintyResult& r) {
  const std::size_t k = r.plan.inputs.size();
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
      const double v = choices.empty() ? spreads.spread[i].quantile(runs[run][i])
                                       : std::min(static_cast<double>(choices.size() - 1), std::floor(runs[run][i] * static_cast<double>(choices.size())));
      const std::string text = !choices.empty()              ? choices[static_cast<std::size_t>(v)]
                               : spreads.ends[i].first.unit.empty() ? fmt::format("{:.17g}", v)
                                                            : fmt::format("{:.17g} {}", v, spreads.ends[i].first.unit);
      settings.push_back(make_setting(spreads.info[i], text, file, r.plan.inputs[i].line, r.plan.inputs[i].parameter));
      values.push_back(v);
      apply_to_document(settings.back(), doc,
                        drawn_by(file, r.plan.inputs[i], r.plan.defaults ? fmt::format("(default) {}", r.plan.inputs[i].parameter)
                                                                          : fmt::format("uncertainty.inputs[{}]", i + 1)));
    }
    r.values.push_back(values);
    if (journal && journal->recall)
      if (const auto kept = journal->recall(run); kept && kept->outputs.size() == r.output_info.size()) {
        r.runs.push_back(*kept);
        r.outputs.push_back(kept->outputs);
        continue;
      }
    // Each input's ends were read alone; together they may still make a scenario the reader
    // refuses: named with the draw, never run.
    const std::string draw = fmt::format("draw {} ({})", run + 1, draw_inputs(r.plan, values));
    std::optional<scenario::Scenario> read;
    try {
      read = scenario::read_scenario(doc, file);
      for (const auto& st : settings) apply(st, *read);
    } catch (const InputError& e) {
      throw InputError(file, std::nullopt, "uncertainty", draw, std::string("the inputs drawn together make a scenario that is refused: ") + e.what());
    } catch (const std::invalid_argument& e) {
      throw InputError(file, std::nullopt, "uncertainty", draw, e.what());
    }
    scenario::Scenario& sc = *read;
    std::string invalid;
    UqRun out = pipeline.assess(sc, nominal, r.plan.size(), threads, invalid);
    if (!invalid.empty())
      throw InputError(file, std::nullopt, "uncertainty", draw, fmt::format("{} is invalid at this draw: {}", pipeline.assessment_words(), invalid));
    if (out.outputs.size() != r.output_info.size())  // (cannot_vary keeps the planes' kinds and sides fixed)
      throw InputError(file, std::nullopt, "uncertainty", draw,
                       fmt::format("this draw gives {} outputs, the study {}: an input changed which figures a draw has", out.outputs.size(),
                                   r.output_info.size()));
    r.runs.push_back(out);
    r.outputs.push_back(out.outputs);
    if (journal && journal->record) journal->record(run, out);
  }
}

// Draws near the cut-off limit, and hazard distances at the tallied range's edge, named.
void warn_about_draws(const scenario::Scenario& nominal, const pipeline::Pipeline& pipeline, UncertaintyResult& r) {
  for (std::size_t run = 0; run < r.runs.size(); ++run)
    if (r.runs[run].cut_off_share >= assess::kWarnCutOffShare) {
      const std::string inputs = draw_inputs(r.plan, r.values[run]);
      r.warnings.push_back(fmt::format(
          "draw {} ({}): {:.2f} % of {} were cut off still moving, mostly by {}, nearing the {:g} % at which a run is "
          "invalid",
          run + 1, inputs, 100 * r.runs[run].cut_off_share, pipeline.cut_off_words(),
          flight::cut_off_name(static_cast<flight::CutOff>(r.runs[run].cut_off_limit)),
          100 * assess::kMaxCutOffShare));
    }
  // What the pipeline has to say of each draw's outputs (a hazard distance at the edge of the
  // ground tallied, say).
  for (std::size_t run = 0; run < r.runs.size(); ++run)
    pipeline.warn(nominal, r.output_info, r.outputs[run], fmt::format("draw {} ({})", run + 1, draw_inputs(r.plan, r.values[run])), r.warnings);
}

// Each output's Sobol' indices (and from the first half of the draws, to show how settled
// they are), and for a J232 test the variance chance alone would give its shares.
void estimate_indices(const scenario::Scenario& nominal, const pipeline::Pipeline& pipeline, int threads, UncertaintyResult& r) {
  const std::size_t outputs = r.output_info.size();
  const auto column = [&](std::size_t o) {
    std::vector<double> f;
    for (const auto& out : r.outputs) f.push_back(out[o]);
    return f;
  };
  for (std::size_t o = 0; o < outputs; ++o) r.indices.push_back(sobol_indices(r.design, column(o), 500, 1));
  // Rare marks (a few in a draw's 7 500 nails) vary from draw to draw by chance as much as by
  // the inputs: what the noise alone would give says how far their indices can be read.
  const std::size_t base_runs = std::min(r.outputs.size(), 2 * r.design.base);  // A and B, as the variance
  r.noise_variance = pipeline.noise_variance(nominal, r.plan.size(), r.output_info, r.outputs, base_runs, threads);
  if (r.design.base >= 4) {
    r.half_indices.emplace();
    for (std::size_t o = 0; o < outputs; ++o) r.half_indices->push_back(sobol_indices_prefix(r.design, column(o), r.design.base / 2, 500, 1));
  }
}

}  // namespace

UncertaintyResult run_uncertainty(const std::string& file, int threads, const std::function<void(std::size_t, std::size_t)>& on_run,
                                  const UncertaintyJournal* journal) {
  const toml::table base = scenario::parse_toml_file(file);
  const scenario::Scenario nominal = scenario::read_scenario(base, file);
  const pipeline::Pipeline& pipeline = pipeline::pipeline_of(nominal);
  UncertaintyResult r;
  r.plan = uncertainty_plan(nominal);
  r.scenario_file = file;
  r.title = nominal.title;
  r.seed = nominal.run.seed;
  r.required = nominal.criteria.required_pass_probability;
  r.field = pipeline.kind() == pipeline::Pipeline::Kind::Field;
  r.acceptable_area = nominal.field.acceptable_area;
  r.output_info = pipeline.outputs(nominal);
  r.smooth_output = pipeline.smooth_output(nominal, r.output_info);
  const InputSpreads spreads = read_spreads(base, file, pipeline, r);
  r.design = saltelli_design(r.plan.inputs.size(), r.plan.base_draws);
  run_draws(base, file, nominal, pipeline, spreads, threads, on_run, journal, r);
  warn_about_draws(nominal, pipeline, r);
  estimate_indices(nominal, pipeline, threads, r);
  return r;
}

}  // namespace j232::study
