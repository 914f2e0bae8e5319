#include "study/uncertainty.hpp"
#include "scenario/ground_kinds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "assess/cluster.hpp"
#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "field/hazard_run.hpp"
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
// The limit that cut off the most (0, none, when none was cut off).
int commonest_cut_off(const std::array<std::uint64_t, flight::kCutOffReasons>& by) {
  int most = 0;
  for (int why = 1; why < flight::kCutOffReasons; ++why)
    if (by[static_cast<std::size_t>(why)] > by[static_cast<std::size_t>(most)]) most = why;
  return most;
}

// A J232 test at one draw: common random numbers (the same seed and replicates at every
// draw). Sets `invalid` to the reason when the simulated test is invalid.
UqRun assess_test(scenario::Scenario& sc, const UncertaintyPlan& plan, int threads, double required, std::string& invalid) {
  sc.run.replicates = plan.replicates;
  sc.run.target_half_width.reset();
  sc.run.until_settled = false;
  const assess::Simulator sim(sc);
  const auto a = assess::run_assessment(sim, threads);
  const auto sum = assess::summarise(a, sc);
  if (!sum.validity.valid) invalid = sum.validity.reasons.front();
  // (From every nail where it can be computed; else, for the `marks` denominator, the
  // replicates' share, as uq.json says.)
  const double exact = sum.exact.computed ? sum.exact.value : sum.pass.estimate;
  UqRun out;
  out.outputs = {sum.pass.estimate,          exact,
                 sum.criteria[0].mean_share, sum.criteria[1].mean_share,
                 sum.criteria[2].mean_share, sum.criteria[3].mean_share,
                 exact >= required ? 1.0 : 0.0};
  const auto cut = sum.fates[static_cast<std::size_t>(flight::Fate::CutOff)];
  out.cut_off_share = sum.struck ? static_cast<double>(cut) / static_cast<double>(sum.struck) : 0.0;
  out.cut_off_limit = commonest_cut_off(sum.cut_off_by);
  return out;
}

// A field at one draw: the same objects (seed and count) at every draw. In an MPI job rank
// 0 holds the whole tally and hands every rank the outputs, so all ranks go on alike.
UqRun assess_field(scenario::Scenario& sc, const UncertaintyPlan& plan, int threads, std::string& invalid) {
  sc.field.objects_simulated = plan.objects;
  const field::FieldSimulator sim(sc);
  const field::HazardRun run = field::run_hazard(sim, threads);
  UqRun out;
  std::string text;
  if (assess::cluster::is_writer()) {
    const field::HazardSummary sum = field::summarise(sim, run);
    out.outputs.push_back(sum.thrown_per_km);
    bool acceptable = true;
    for (const auto& d : sum.directions) {
      out.outputs.push_back(d.hazard_distance);
      acceptable = acceptable && !d.beyond_range && d.hazard_distance <= d.deck_extent;
    }
    for (const auto& p : sum.planes) {
      out.outputs.push_back(p.hazardous_per_km.value);
      if (p.plane.receptor == scenario::FieldPlaneSpec::Receptor::Person && p.along_path) out.outputs.push_back(p.probability.value);
    }
    out.outputs.push_back(acceptable ? 1.0 : 0.0);
    out.cut_off_share = sum.cut_off_share;
    std::array<std::uint64_t, flight::kCutOffReasons> by{};
    for (const auto& t : run.kinds)
      for (std::size_t why = 0; why < by.size(); ++why) by[why] += t.cut_off_by[why];
    out.cut_off_limit = commonest_cut_off(by);
    if (!sum.valid) invalid = sum.invalid_reason;
    text = invalid + '\n' + fmt::format("{:.17g} {}", out.cut_off_share, out.cut_off_limit);
    for (double v : out.outputs) text += fmt::format(" {:.17g}", v);
  }
  if (assess::cluster::size() > 1) {
    assess::cluster::broadcast_from_writer(text);
    const auto line = text.find('\n');
    invalid = text.substr(0, line);
    // (strtod reads back whatever {:.17g} wrote, "nan" and "inf" included.)
    const std::string numbers = text.substr(line + 1);
    const char* at = numbers.c_str();
    char* end = nullptr;
    out.cut_off_share = std::strtod(at, &end);
    out.cut_off_limit = static_cast<int>(std::strtol(end, &end, 10));
    out.outputs.clear();
    for (at = end; *at != '\0'; at = end) {
      const double v = std::strtod(at, &end);
      if (end == at) break;
      out.outputs.push_back(v);
    }
  }
  return out;
}

// Why a key cannot be an uncertain input of a study (empty: it can).
std::string cannot_vary(const std::string& key, bool field) {
  if (key == "run.seed")
    return "every draw runs with the scenario's seed (common random numbers, so that draws differ by their inputs, not by noise); "
           "a seed drawn would undo that";
  if (key == "run.replicates") return "each assessment runs [uncertainty] replicates; set that instead";
  if (key == "field.objects_simulated") return "each assessment simulates [uncertainty] objects; set that instead";
  if (key.rfind("field.planes", 0) == 0 && !(key.size() >= 9 && key.compare(key.size() - 9, 9, ".distance") == 0))
    return "a plane's side, receptor and name decide which figures the study judges; only its distance can be drawn";
  if (field && (key == "air.cd_normal" || key == "air.cd_axial"))
    return "a field's objects are spheres: their drag is field.objects[N].drag_coefficient";
  return "";
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


std::vector<UqOutput> uq_outputs(const scenario::Scenario& s) {
  using Scale = UqOutput::Scale;
  if (!s.field.present)
    return {{"p_pass", "P(pass one test)", Scale::Probability, ""},
            {"p_pass_exact", "P(pass) from every nail (exact)", Scale::Probability, ""},
            {"hits_zone", "hits in the operator zone", Scale::Percent, ""},
            {"punctures_zone", "punctures in the operator zone", Scale::Percent, ""},
            {"hits_outside", "hits outside the zone", Scale::Percent, ""},
            {"punctures_outside", "punctures outside the zone", Scale::Percent, ""},
            {"passes", "passes (P(pass) at least the required)", Scale::Number, ""}};
  std::vector<UqOutput> out = {{"thrown_per_km", "objects thrown per km mowed", Scale::Number, " per km"}};
  for (const char* d : {"left", "right", "front", "rear"})
    out.push_back({fmt::format("hazard_distance_{}", d), fmt::format("hazard distance to the {}", d), Scale::Number, " m"});
  for (std::size_t i = 0; i < s.field.planes.size(); ++i) {
    const auto& p = s.field.planes[i];
    const bool person = p.receptor == scenario::FieldPlaneSpec::Receptor::Person;
    // Named with the plane's distance: two planes of one name (the default is the side) stay apart.
    const std::string plane = fmt::format("{} at {:g} m", p.name, p.distance);
    out.push_back({fmt::format("plane{}_hazardous_per_km", i + 1),
                   fmt::format("{}: hazardous {} per km", plane, person ? "crossings of a person's height" : "impacts on the windshield band"),
                   Scale::Number, " per km"});
    const bool beside = p.side == scenario::FieldPlaneSpec::Side::Left || p.side == scenario::FieldPlaneSpec::Side::Right;
    if (person && beside)
      out.push_back({fmt::format("plane{}_p_struck", i + 1), fmt::format("{}: P(a person there is struck in one pass)", plane),
                     Scale::Probability, ""});
  }
  out.push_back({"acceptable_beyond_deck", "acceptable beyond the deck (hazard distance at the deck's edge every way)", Scale::Number, ""});
  return out;
}

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

namespace {
UncertainInput estimated(std::string parameter, std::string low, std::string high, std::string basis, std::string distribution = "uniform") {
  UncertainInput in;
  in.parameter = std::move(parameter), in.low = std::move(low), in.high = std::move(high), in.basis = std::move(basis);
  in.distribution = std::move(distribution);
  return in;
}

// A choice of the model's own form, drawn with the inputs (issue: a verdict that rests on
// one contact model is not shown to rest on it until the other is drawn too).
UncertainInput model_form(std::string parameter, std::vector<std::string> values, std::string basis) {
  UncertainInput in;
  in.parameter = std::move(parameter), in.values = std::move(values), in.basis = std::move(basis);
  return in;
}

// The contact model: both forms are defensible and neither is exact (docs/model.md §5.3).
UncertainInput contact_model_form() {
  return model_form("contacts.model", {"sequential", "simultaneous"},
                    "model form: the contacts of one instant one after another, or together (Moreau's impact); neither is exact "
                    "for a rod's multiple impacts (Stoianovici and Hurmuzlu 1996)");
}

// The restitution law of every impact (docs/model.md §5.1c).
UncertainInput restitution_law_form() {
  return model_form("run.restitution_law", {"energetic", "poisson"},
                    "model form: Stronge's energetic restitution, or Poisson's (the earlier law); the two agree without "
                    "friction and differ where the slip halts or reverses within an impact");
}

// What the test's mower stands on: the test's text is not to hand, so every kind of the
// table is drawn. Each kind carries its own restitution, friction, roughness and
// penetrability (docs/model.md §5.3a), so neither its restitution nor the angle law's cap is
// drawn beside it (a drawn value would override every kind's own, and a cap below a hard
// kind's restitution is refused).
UncertainInput ground_kind_form() {
  std::vector<std::string> kinds;
  for (const auto& k : scenario::kGroundKinds) kinds.emplace_back(k.name);
  return model_form("ground.kind", kinds,
                    "set-up: what the test ground is (SAE J232's text on it not to hand); each kind with its own restitution, friction "
                    "and penetrability (recalled tables and estimates)");
}

// How open the chain curtains are: one input for every guard when all are chains, else one
// per chain guard (a flap is a solid plate: it has no openness to draw).
std::vector<UncertainInput> guard_openness(const scenario::Scenario& s) {
  const auto& guards = s.housing.guards;
  const auto chains = static_cast<std::size_t>(std::count_if(guards.begin(), guards.end(), [](const auto& g) { return g.kind == scenario::GuardSpec::Kind::Chains; }));
  const char* basis = "estimate: single row 0.3-0.5 open, double row 0.1-0.25";
  if (chains == 0) return {};
  if (chains == guards.size()) return {estimated("housing.guards.openness", "0.1", "0.4", basis)};
  std::vector<UncertainInput> out;
  for (std::size_t k = 0; k < guards.size(); ++k)
    if (guards[k].kind == scenario::GuardSpec::Kind::Chains)
      out.push_back(estimated(fmt::format("housing.guards[{}].openness", k + 1), "0.1", "0.4", basis));
  return out;
}

// A field's estimated inputs (docs/model.md §9): what is known of the field (how many
// objects, how large, how deep in the turf), of the air under the deck and of the contacts,
// each over a range about the scenario's own value.
std::vector<UncertainInput> field_defaults(const scenario::Scenario& s) {
  const auto& f = s.field;
  // Where a blade can reach an object (its lowest face) and where objects enter the deck
  // (the front's gap), as the reader checks them: every draw must keep each kind able to
  // pass under the front and to reach a blade, standing up to it or lifted by the updraft.
  const double lowest_face = s.lowest_blade_face();
  const std::optional<double> front_gap = s.front_gap();
  // The least updraft that lifts the kind's smallest (with a 5 % margin) at drag
  // coefficient cd: the size lifted grows as u^2.
  const auto lifting = [&](const scenario::FieldObjectSpec& o, double cd) {
    return std::sqrt(1.05 * o.min_size / s.lifted_up_to(o, cd, 1.0));
  };
  double updraft_low = 0.75 * f.updraft_speed;
  std::vector<UncertainInput> kinds;
  for (std::size_t k = 0; k < f.objects.size(); ++k) {
    const auto& o = f.objects[k];
    const std::string at = fmt::format("field.objects[{}].", k + 1);
    kinds.push_back(estimated(at + "per_area", fmt::format("{:.4g} m^-2", 0.5 * o.per_area), fmt::format("{:.4g} m^-2", 2 * o.per_area),
                              fmt::format("estimate: {} per m2 is not surveyed; within a factor of 2, uniform in its logarithm", o.name),
                              "loguniform"));
    if (o.kind != scenario::FieldObjectSpec::Kind::Stone) continue;  // a steel ball's size, density and drag are known
    if (o.min_size < o.max_size) {
      // Kept a little inside min and max, so that the ends written to four digits stay inside.
      const double lo = std::max(o.min_size * 1.001, o.median_size / 1.5), hi = std::min(o.max_size * 0.999, o.median_size * 1.5);
      if (hi > lo)
        kinds.push_back(estimated(at + "median_size", fmt::format("{:.4g} mm", 1000 * lo), fmt::format("{:.4g} mm", 1000 * hi),
                                  fmt::format("estimate: the median size of the {} within a factor of 1.5 (inside its min and max)", o.name),
                                  "loguniform"));
    }
    // Sunk deeper, the largest must still stand up to the blade's lower face (unless the
    // updraft lifts them); less deep, still pass under the deck's front.
    const double stands_until = 1 - lowest_face / o.max_size - 0.01;  // deeper than this, none stands up to the blade
    const double deepest = std::min({0.9, o.embedment + 0.1, std::max(o.embedment, stands_until)});
    const double shallowest = std::max({0.0, o.embedment - 0.1, front_gap ? std::min(o.embedment, 1 - *front_gap / o.max_size + 0.01) : 0.0});
    // Only where some stand up to the blade at the shallow end does the embedment matter:
    // objects lifted into the blades' plane meet them there, however deep they lay.
    if (deepest > shallowest && o.max_size * (1 - shallowest) > lowest_face)
      kinds.push_back(estimated(at + "embedment", fmt::format("{:.3g}", shallowest), fmt::format("{:.3g}", deepest),
                                fmt::format("estimate: how deep the {} sit in the turf, the scenario's share +/- 0.1 (no deeper than leaves "
                                            "the largest standing up to the blade, unless the updraft lifts them; no shallower than lets "
                                            "it pass under the deck's front)",
                                            o.name)));
    if (o.restitution)
      kinds.push_back(estimated(at + "restitution", fmt::format("{:.3g}", std::min(0.3, *o.restitution)), fmt::format("{:.3g}", std::max(0.7, *o.restitution)),
                                "estimate: stone on hardened steel, 0.3-0.7 (and the scenario's value); no measurement at blade speeds"));
    double cd_low = std::min(0.47, o.drag_coefficient);
    const double cd_high = std::max(0.8, o.drag_coefficient);
    if (o.max_size * (1 - deepest) <= lowest_face) {
      // Lifted or not reached at all: the updraft's low end with the drag's must still lift
      // the smallest. Raised to do so; where even the scenario's drag needs more than the
      // updraft's low end, the drag's low end is the scenario's.
      if (lifting(o, cd_low) >= f.updraft_speed) cd_low = o.drag_coefficient;
      updraft_low = std::max(updraft_low, std::min(lifting(o, cd_low), f.updraft_speed));
    }
    kinds.push_back(estimated(at + "drag_coefficient", fmt::format("{:.3g}", cd_low), fmt::format("{:.3g}", cd_high),
                              "handbook: a smooth sphere 0.47; angular stones up to about 0.8 (estimate; and the scenario's value)"));
    if (o.kind == scenario::FieldObjectSpec::Kind::Stone)
      kinds.push_back(model_form(at + "rolls", {"false", "true"},
                                 fmt::format("model form: angular {} skid on the ground and do not roll along the mower's steel, rounded ones roll; "
                                             "how round a field's stones are is not surveyed",
                                             o.name)));
  }
  std::vector<UncertainInput> in;
  if (f.updraft_speed > 0 && updraft_low < f.updraft_speed)
    in.push_back(estimated("field.updraft_speed", fmt::format("{:.4g} m/s", updraft_low), fmt::format("{:.4g} m/s", 1.25 * f.updraft_speed),
                           updraft_low > 0.75 * f.updraft_speed
                               ? "estimate: no measurement of the air under a deck at the turf; the scenario's value + 25 %, and down to "
                                 "where it still lifts the smallest objects that reach a blade only when lifted"
                               : "estimate: no measurement of the air under a deck at the turf; the scenario's value +/- 25 %"));
  if (f.support_height > 0)
    in.push_back(estimated("field.support_height", fmt::format("{:.4g} mm", 500 * f.support_height), fmt::format("{:.4g} mm", 2000 * f.support_height),
                           "estimate: no survey of what holds objects up on a mowed verge (ground roughness, thatch, clumps); "
                           "within a factor of 2, uniform in its logarithm",
                           "loguniform"));
  if (f.support_height > 0)
    in.push_back(model_form("field.support_shape", {"exponential", "half_normal"},
                            "model form: how the supports' heights are spread about their mean (a long tail of tall ones, or "
                            "fewer); not surveyed, and at high cuts it decides how many objects reach a blade"));
  in.insert(in.end(), kinds.begin(), kinds.end());
  in.push_back(estimated("bevel_angle", "20 deg", "45 deg", "estimate: mower blades are ground to about 30 deg; no figure for industrial cutters"));
  in.push_back(estimated("ground.restitution", "0.1", "0.25", "estimate: rockfall field data give a normal e of about 0.2"));
  in.push_back(estimated("ground.max_restitution", "0.5", "0.95", "estimate: the angle law passes 1 at grazing impacts; a bounce off turf loses energy"));
  in.push_back(estimated("ground.rolling_resistance", "0.1", "0.6",
                         "estimate: a ball rolling on a golf green slows by 0.05-0.09 g and on a football pitch by about 0.07-0.2 g; "
                         "a verge mowed at 3-6 in, taller, more"));
  for (auto& guard : guard_openness(s)) in.push_back(std::move(guard));
  in.push_back(contact_model_form());
  in.push_back(restitution_law_form());
  return in;
}
}  // namespace

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
  UncertaintyPlan plan;
  plan.base_draws = static_cast<std::size_t>(s.uncertainty.base_draws);
  plan.replicates = s.uncertainty.replicates;
  if (s.field.present) plan.objects = s.uncertainty.objects.value_or(std::min(s.field.objects_simulated, 20000LL));
  if (!s.uncertainty.inputs.empty()) {
    plan.inputs = s.uncertainty.inputs;
    return plan;
  }
  plan.defaults = true;
  if (s.field.present) {
    plan.inputs = field_defaults(s);
    return plan;
  }
  // The estimated inputs (docs/model.md §8), each over a range with its basis.
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
      estimated("housing.friction", "0.3", "0.6", "handbook: steel on steel, kinetic 0.42-0.57"),
      estimated("feed.tilt_max", "0 deg", "10 deg", "estimate: SAE J232's feed tube geometry is not available"),
  };
  for (auto& guard : guard_openness(s)) plan.inputs.push_back(std::move(guard));
  plan.inputs.push_back(ground_kind_form());
  plan.inputs.push_back(contact_model_form());
  plan.inputs.push_back(restitution_law_form());
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

InputSpreads read_spreads(const toml::table& base, const std::string& file, const UncertaintyResult& r) {
  const std::size_t k = r.plan.inputs.size();
  InputSpreads spreads;
  for (std::size_t i = 0; i < k; ++i) {
    const UncertainInput& in = r.plan.inputs[i];
    const std::string key = r.plan.defaults ? fmt::format("(default) {}", in.parameter) : fmt::format("uncertainty.inputs[{}]", i + 1);
    spreads.info.push_back(parameter_info(in.parameter));
    if (const std::string why = cannot_vary(in.parameter, r.field); !why.empty())
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

// The output the inputs are ranked by: a smooth one (P(pass) from every nail; in a field, the
// hazardous flux at the first plane a person stands at, else the first plane's, else the
// objects thrown).
std::size_t smooth_output(const UncertaintyResult& r, const scenario::Scenario& nominal) {
  std::size_t chosen = 1;
  if (r.field) {
    const auto& planes = nominal.field.planes;
    const auto person = std::find_if(planes.begin(), planes.end(), [](const auto& p) { return p.receptor == scenario::FieldPlaneSpec::Receptor::Person; });
    const auto plane = person != planes.end() ? person - planes.begin() : planes.empty() ? -1 : 0;
    const std::string name = fmt::format("plane{}_hazardous_per_km", plane + 1);
    chosen = 0;
    for (std::size_t o = 0; o < r.output_info.size(); ++o)
      if (plane >= 0 && r.output_info[o].name == name) chosen = o;
  }
  return chosen;
}

// Every draw of the Saltelli design: the scenario with the drawn inputs written in, read and
// assessed (or recalled from the journal of an interrupted study), its outputs recorded.
void run_draws(const toml::table& base, const std::string& file, const InputSpreads& spreads, int threads,
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
    UqRun out = r.field ? assess_field(sc, r.plan, threads, invalid) : assess_test(sc, r.plan, threads, r.required, invalid);
    if (!invalid.empty())
      throw InputError(file, std::nullopt, "uncertainty", draw,
                       (r.field ? "the hazard run is invalid at this draw: " : "the simulated test is invalid at this draw: ") + invalid);
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
void warn_about_draws(const scenario::Scenario& nominal, UncertaintyResult& r) {
  for (std::size_t run = 0; run < r.runs.size(); ++run)
    if (r.runs[run].cut_off_share >= assess::kWarnCutOffShare) {
      const std::string inputs = draw_inputs(r.plan, r.values[run]);
      r.warnings.push_back(fmt::format(
          "draw {} ({}): {:.2f} % of {} were cut off still moving, mostly by {}, nearing the {:g} % at which a run is "
          "invalid",
          run + 1, inputs, 100 * r.runs[run].cut_off_share, r.field ? "the objects" : "struck nails",
          flight::cut_off_name(static_cast<flight::CutOff>(r.runs[run].cut_off_limit)),
          100 * assess::kMaxCutOffShare));
    }
  // A hazard distance at the range's edge lies there or beyond: the number understates it.
  if (r.field)
    for (std::size_t run = 0; run < r.runs.size(); ++run)
      for (std::size_t o = 0; o < r.output_info.size(); ++o)
        if (r.output_info[o].name.rfind("hazard_distance_", 0) == 0 && r.outputs[run][o] >= nominal.field.range * (1 - 1e-9))
          r.warnings.push_back(fmt::format("draw {} ({}): the {} reaches the edge of the ground tallied (field.range, {:g} m): it lies "
                                           "there or beyond, and the figure {:g} m understates it",
                                           run + 1, draw_inputs(r.plan, r.values[run]), r.output_info[o].words, nominal.field.range,
                                           r.outputs[run][o]));
}

// Each output's Sobol' indices (and from the first half of the draws, to show how settled
// they are), and for a J232 test the variance chance alone would give its shares.
void estimate_indices(const scenario::Scenario& nominal, UncertaintyResult& r) {
  const std::size_t outputs = r.output_info.size();
  const auto column = [&](std::size_t o) {
    std::vector<double> f;
    for (const auto& out : r.outputs) f.push_back(out[o]);
    return f;
  };
  for (std::size_t o = 0; o < outputs; ++o) r.indices.push_back(sobol_indices(r.design, column(o), 500, 1));
  // Rare marks (a few in a draw's 7 500 nails) vary from draw to draw by chance as much as by
  // the inputs: what the noise alone would give says how far their indices can be read.
  r.noise_variance.assign(outputs, -1.0);
  if (!r.field) {
    const double replicates = static_cast<double>(r.plan.replicates), nails = static_cast<double>(nominal.feed.nails);
    const std::size_t base_runs = std::min(r.outputs.size(), 2 * r.design.base);  // A and B, as the variance
    for (std::size_t o = 0; o < outputs && base_runs > 0; ++o) {
      const auto& output = r.output_info[o];
      const bool share_of_nails = output.scale == UqOutput::Scale::Percent && nominal.criteria.denominator == scenario::CriteriaSpec::Denominator::NailsFed;
      const double trials = output.name == "p_pass" ? replicates : share_of_nails ? replicates * nails : 0.0;
      if (!(trials > 0)) continue;
      double sum = 0;
      for (std::size_t run = 0; run < base_runs; ++run) sum += r.outputs[run][o] * (1 - r.outputs[run][o]) / trials;
      r.noise_variance[o] = sum / static_cast<double>(base_runs);
    }
  }
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
  UncertaintyResult r;
  r.plan = uncertainty_plan(nominal);
  r.scenario_file = file;
  r.title = nominal.title;
  r.seed = nominal.run.seed;
  r.required = nominal.criteria.required_pass_probability;
  r.field = nominal.field.present;
  r.acceptable_area = nominal.field.acceptable_area;
  r.output_info = uq_outputs(nominal);
  r.smooth_output = smooth_output(r, nominal);
  const InputSpreads spreads = read_spreads(base, file, r);
  r.design = saltelli_design(r.plan.inputs.size(), r.plan.base_draws);
  run_draws(base, file, spreads, threads, on_run, journal, r);
  warn_about_draws(nominal, r);
  estimate_indices(nominal, r);
  return r;
}

}  // namespace j232::study
