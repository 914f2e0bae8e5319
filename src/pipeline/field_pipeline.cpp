// The field as a study's pipeline: a hazard run over the same objects at each draw, judged
// by its rates, hazard distances and planes (docs/model.md §9).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <stdexcept>
#include <string>

#include "field/hazard_run.hpp"
#include "invariant/check.hpp"
#include "pipeline/estimated_inputs.hpp"
#include "pipeline/pipeline.hpp"
#include "scenario/input_error.hpp"

namespace j232::pipeline {

namespace {

// A field's estimated inputs (docs/model.md §9): what is known of the field (how many
// objects, how large, how deep in the turf), of the air under the deck and of the contacts,
// each over a range about the scenario's own value.
std::vector<scenario::UncertainInput> field_defaults(const scenario::Scenario& s) {
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
  std::vector<scenario::UncertainInput> kinds;
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
  std::vector<scenario::UncertainInput> in;
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
  // Only a field's stones are held on a knife's face (a nail never is): drawn here alone.
  in.push_back(model_form("contacts.blade_push", {"held", "impacts"},
                          "model form: a knife's push on a stone held on its face as one sliding contact, or followed contact by "
                          "contact; the two agree within the runs' noise on the shipped fields"));
  return in;
}

// A plane's name as a CSV column's stem: lower case, a run of anything else one '_'.
std::string column_stem(const std::string& name) {
  std::string o;
  for (char c : name) {
    const bool word = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
    const bool upper = c >= 'A' && c <= 'Z';
    if (word || upper) o += upper ? static_cast<char>(c - 'A' + 'a') : c;
    else if (!o.empty() && o.back() != '_') o += '_';
  }
  while (!o.empty() && o.back() == '_') o.pop_back();
  return o.empty() ? "plane" : o;
}

constexpr long long kUqObjectsPerStratum = 30;

// A hazard run's figures in the order of Field::outputs, each with its Monte Carlo variance
// in that run (-1: none estimated).
struct Figures {
  std::vector<double> values, noise;
  void add(double value, double variance) { values.push_back(value), noise.push_back(variance); }
};
Figures figures(const field::HazardSummary& sum) {
  Figures f;
  f.add(sum.thrown_per_km, sum.thrown_per_km_variance);
  bool acceptable = true;
  for (const auto& d : sum.directions) {
    f.add(d.hazard_distance, -1.0);
    acceptable = acceptable && !d.beyond_range && d.hazard_distance <= d.deck_extent;
  }
  for (const auto& p : sum.planes) {
    f.add(p.hazardous_per_km.value, p.hazardous_per_km.variance);
    if (p.plane.receptor == scenario::FieldPlaneSpec::Receptor::Person && p.along_path) f.add(p.probability.value, p.probability.variance);
  }
  f.add(acceptable ? 1.0 : 0.0, -1.0);
  return f;
}

class Field final : public Pipeline {
 public:
  Kind kind() const override { return Kind::Field; }
  const char* assessment_words() const override { return "the hazard run"; }
  const char* cut_off_words() const override { return "the objects"; }

  // Objects thrown per km, the hazard distance in each direction, each plane's hazardous
  // flux (and a person's probability of being struck there), and whether the ground beyond
  // the deck is acceptable.
  std::vector<Output> outputs(const scenario::Scenario& s) const override {
    using Scale = Output::Scale;
    std::vector<Output> out = {{"thrown_per_km", "objects thrown per km mowed", Scale::Number, " per km"}};
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
  // The hazardous flux at the first plane a person stands at, else the first plane's, else
  // the objects thrown.
  std::size_t smooth_output(const scenario::Scenario& nominal, const std::vector<Output>& info) const override {
    const auto& planes = nominal.field.planes;
    const auto person = std::find_if(planes.begin(), planes.end(), [](const auto& p) { return p.receptor == scenario::FieldPlaneSpec::Receptor::Person; });
    const auto plane = person != planes.end() ? person - planes.begin() : planes.empty() ? -1 : 0;
    const std::string name = fmt::format("plane{}_hazardous_per_km", plane + 1);
    std::size_t chosen = 0;
    for (std::size_t o = 0; o < info.size(); ++o)
      if (plane >= 0 && info[o].name == name) chosen = o;
    return chosen;
  }

  std::vector<scenario::UncertainInput> estimated_inputs(const scenario::Scenario& s) const override { return field_defaults(s); }
  std::string cannot_vary(const std::string& key) const override {
    if (key == "air.cd_normal" || key == "air.cd_axial") return "a field's objects are spheres: their drag is field.objects[N].drag_coefficient";
    return "";
  }
  // By default 30 objects of each size stratum (120 of a kind), at most the scenario's own
  // count: the shipped shoulder's study (256 base draws of 21 inputs, 5 888 hazard runs of 240
  // objects) takes about 9 1/2 minutes on 2 cores, and chance gives under 1 % of the
  // variance over the draws of each rate it estimates (uq.json noise_share; docs/validation.md §5).
  DrawSize draw_size(const scenario::Scenario& s) const override {
    const auto per_kind = static_cast<long long>(field::FieldSimulator::kSizeStrata) * kUqObjectsPerStratum;
    const auto objects = per_kind * static_cast<long long>(s.field.objects.size());
    return {s.uncertainty.replicates, s.uncertainty.objects.value_or(std::min(s.field.objects_simulated, objects))};
  }

  // The same objects (seed and count) at every draw. Every rank of an MPI job holds the whole
  // tally (field::run_hazard), so all return the same.
  DrawOutputs assess(scenario::Scenario& sc, const scenario::Scenario&, const DrawSize& size, int threads,
                     std::string& invalid) const override {
    sc.field.objects_simulated = size.objects;
    const field::FieldSimulator sim(sc);
    const field::HazardRun run = field::run_hazard(sim, threads);
    const field::HazardSummary sum = field::summarise(sim, run);
    DrawOutputs out;
    out.outputs = figures(sum).values;
    out.cut_off_share = sum.cut_off_share;
    std::array<std::uint64_t, flight::kCutOffReasons> by{};
    for (const auto& t : run.strata)
      for (std::size_t why = 0; why < by.size(); ++why) by[why] += t.cut_off_by[why];
    out.cut_off_limit = commonest_cut_off(by);
    if (!sum.valid) invalid = sum.invalid_reason;
    return out;
  }

  // A hazard distance at the range's edge lies there or beyond: the number understates it.
  void warn(const scenario::Scenario& nominal, const std::vector<Output>& info, const std::vector<double>& outputs, const std::string& name,
            std::vector<std::string>& warnings) const override {
    for (std::size_t o = 0; o < info.size(); ++o)
      if (info[o].name.rfind("hazard_distance_", 0) == 0 && outputs[o] >= nominal.field.range * (1 - 1e-9))
        warnings.push_back(fmt::format("{}: the {} reaches the edge of the ground tallied (field.range, {:g} m): it lies "
                                       "there or beyond, and the figure {:g} m understates it",
                                       name, info[o].words, nominal.field.range, outputs[o]));
  }
  std::string refuse_parameter(const std::string& name, const scenario::Scenario& s) const override {
    const auto& objects = s.field.objects;
    if (name == "restitution" && std::all_of(objects.begin(), objects.end(), [](const auto& o) { return o.restitution.has_value(); }))
      return "restitution: every object of this field has its own restitution on the blade (field.objects[N].restitution)";
    if (name == "contact_radius") return "contact_radius: a field scenario has no feed; its objects lie across the cut";
    if (name == "object_mass") return "object_mass: a field's objects take their mass from their size and density (field.objects[N].median_size)";
    if (name == "object_speed") return "object_speed: a field's objects lie still until struck; vary field.ground_speed instead";
    if (name == "edge_friction") return "edge_friction: a field's objects have their own friction on the blade (field.objects[N].friction)";
    return "";
  }
  std::string refuse_drivers() const override { return "a field has no deciding criterion: its drivers are j232 uq's"; }

  std::vector<std::string> sweep_columns() const override {
    return {"objects", "reaching_per_km", "thrown_per_km", "last_strike_speed_m_s", "cut_off_percent"};  // then per direction and plane
  }
  std::optional<Refusal> refuse_sweep_size(const DrawSize& size) const override {
    if (size.replicates > 0)
      return Refusal{"run.replicates", std::to_string(size.replicates), "a field scenario's sweep takes run.objects (objects per point), not replicates"};
    return std::nullopt;
  }
  // One hazard run. Its columns (the planes' and the directions' names) are the first
  // point's; every point must have the same planes.
  std::vector<double> sweep_point(scenario::Scenario& sc, const DrawSize& size, bool first, int threads, SweepColumns& t,
                                  std::string& invalid) const override {
    if (size.objects > 0) sc.field.objects_simulated = size.objects;
    if (!sc.field.present) throw BrokenSweep("the base is a field scenario at its other points; here it has no [field]");
    std::optional<field::FieldSimulator> made;
    try {
      made.emplace(sc);
    } catch (const scenario::InputError& e) {  // what the point's settings made of the field (no size can reach a blade, say)
      invalid = e.what();
      return {};
    }
    const field::FieldSimulator& sim = *made;
    const field::HazardRun run = field::run_hazard(sim, threads);
    const field::HazardSummary sum = field::summarise(sim, run);
    // A run with too many objects cut off by its limits has no hazard to plot.
    if (!sum.valid) {
      invalid = "the hazard run is invalid here: " + sum.invalid_reason;
      return {};
    }
    std::vector<std::string> planes, directions;
    for (const auto& pl : sum.planes) planes.push_back(pl.plane.name);
    for (const auto& d : sum.directions) directions.push_back(d.direction);
    if (first && t.planes.empty() && t.directions.empty()) {  // the first point assessed names the columns
      t.planes = planes, t.directions = directions;
      for (const auto& d : directions)
        for (const char* c : {"hazard_distance_m", "hazard_distance_upper_m", "beyond_range", "upper_beyond_range"})
          t.columns.push_back(fmt::format("{}_{}", d, c));
      std::vector<std::string> stems;  // unique: two planes of one name get _2, _3...
      for (const auto& name : planes) {
        std::string stem = column_stem(name);
        for (int k = 2; std::find(stems.begin(), stems.end(), stem) != stems.end(); ++k) stem = fmt::format("{}_{}", column_stem(name), k);
        stems.push_back(stem);
      }
      for (const auto& stem : stems)
        for (const char* c : {"hazardous_per_km", "hazardous_per_km_low", "hazardous_per_km_high"})
          t.columns.push_back(fmt::format("plane_{}_{}", stem, c));
    } else if (planes != t.planes || directions != t.directions) {
      throw BrokenSweep("the planes differ from the sweep's first point: every point must tally the same planes");
    }
    std::vector<double> v{static_cast<double>(sum.objects), sum.reaching_per_km, sum.thrown_per_km, sum.last_strike_speed_mean,
                          100 * sum.cut_off_share};
    for (const auto& d : sum.directions)
      v.insert(v.end(), {d.hazard_distance, d.hazard_distance_upper, d.beyond_range ? 1.0 : 0.0, d.upper_beyond_range ? 1.0 : 0.0});
    for (const auto& pl : sum.planes) v.insert(v.end(), {pl.hazardous_per_km.value, pl.hazardous_per_km.low, pl.hazardous_per_km.high});
    return v;
  }

  // From one run of the nominal scenario at the draws' size: each figure's variance from that
  // run's own per-object counts (a rate's weighted counts, the thrown share's binomial,
  // P(struck) to first order); a hazard distance and the acceptable flag have none.
  std::vector<double> noise_variance(const scenario::Scenario& nominal, const DrawSize& size, const std::vector<Output>& info,
                                     const std::vector<std::vector<double>>&, std::size_t, int threads) const override {
    scenario::Scenario sc = nominal;
    sc.field.objects_simulated = size.objects;
    const field::FieldSimulator sim(sc);
    const field::HazardSummary sum = field::summarise(sim, field::run_hazard(sim, threads));
    std::vector<double> noise = figures(sum).noise;
    J232_CHECK(noise.size() == info.size());
    return noise;
  }
};

}  // namespace

const Pipeline& field_pipeline() {
  static const Field pipeline;
  return pipeline;
}

}  // namespace j232::pipeline
