// Running a sweep: every point, each an impact or a whole assessment (study/sweep.hpp).
#include "study/sweep.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <optional>
#include <stdexcept>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "blade/blade_model.hpp"
#include "field/hazard_run.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario_reader.hpp"
#include "scenario/toml_reader.hpp"

namespace j232::study {

namespace {

using scenario::InputError;

double display(const Setting& s) { return s.si / s.info.display_factor; }

struct Point {
  std::size_t series;
  std::vector<const Setting*> settings;  // fixed settings, series values, then x: applied in this order
};

// Every (series combination, x value), first series outermost.
std::vector<Point> points(const SweepSpec& spec, std::vector<std::string>& labels) {
  std::vector<std::vector<const Setting*>> combos{{}};
  for (const auto& axis : spec.series) {
    std::vector<std::vector<const Setting*>> next;
    for (const auto& c : combos)
      for (const auto& v : axis.values) {
        next.push_back(c);
        next.back().push_back(&v);
      }
    combos = std::move(next);
  }
  std::vector<Point> out;
  std::vector<const Setting*> fixed;
  for (const auto& f : spec.fixed) fixed.push_back(&f);
  for (std::size_t s = 0; s < combos.size(); ++s) {
    std::string label;
    for (const auto* v : combos[s])
      label += (label.empty() ? "" : ", ") +
               (v->info.kind == units::Kind::Dimensionless ? fmt::format("{} {}", v->info.name, v->text) : v->text);
    labels.push_back(label);
    for (const auto& x : spec.x.values) {
      out.push_back({s, fixed});
      out.back().settings.insert(out.back().settings.end(), combos[s].begin(), combos[s].end());
      out.back().settings.push_back(&x);
    }
  }
  return out;
}

// The error for a point the base cannot take (a contact off the re-shaped blade, say).
InputError point_error(const SweepSpec& spec, const Point& p, const std::string& what) {
  std::string at;
  for (const auto* s : p.settings) at += (at.empty() ? "" : ", ") + s->info.name + " = " + s->text;
  return InputError(spec.source, std::nullopt, "sweep point", at, what);
}

// A point the sweep cannot assess (the reader refuses what its settings make of the base,
// or its run is invalid): a J232 or field sweep records it and goes on; an impact sweep stops.
struct InvalidPoint {
  explicit InvalidPoint(InputError e, std::optional<InputError> r = std::nullopt) : error(std::move(e)), reader(std::move(r)) {}
  InputError error;                  // naming the point
  std::optional<InputError> reader;  // the reader's own refusal, when it was that
};

// The base with a point's settings: file keys into the document, which is then read
// (with all the reader's checks), then the named parameters onto what was read.
template <class Input, class Read>
Input prepare(const SweepSpec& spec, const Point& p, const toml::table& base, Read read) {
  toml::table doc = base;
  for (const auto* s : p.settings) apply_to_document(*s, doc, spec.source);
  std::optional<Input> input;
  try {
    input.emplace(read(doc, spec.base));
  } catch (const InputError& e) {  // the point's settings make a scenario the reader refuses
    throw InvalidPoint(point_error(spec, p, e.what()), e);
  }
  try {
    for (const auto* s : p.settings) apply(*s, *input);
  } catch (const std::invalid_argument& e) {
    throw InvalidPoint(point_error(spec, p, e.what()));
  }
  return std::move(*input);
}

std::vector<double> impact_point(const SweepSpec& spec, const Point& p, const toml::table& base) {
  const auto c = prepare<scenario::ImpactCase>(spec, p, base, scenario::read_impact_case);
  const auto where = blade::locate(c.blade, c.arm, c.radius);
  if (!where)
    throw point_error(spec, p,
                      fmt::format("the contact radius {:.4g} m is off the blade (tip radius {:.4g} m)", c.radius, c.blade.tip_radius()));
  const auto problems = blade::problems(c.blade);
  if (!problems.empty()) throw point_error(spec, p, problems.front());
  const blade::BladeModel model(c.blade);
  blade::ImpactSolution sol;
  try {
    sol = blade::solve_impact(model, *where, c.object, c.restitution);
  } catch (const std::invalid_argument& e) {
    throw point_error(spec, p, e.what());
  }
  const double v0 = -c.object.velocity.y();
  const double v1 = sol.contact.velocity_after.y();
  const double tip_speed = c.blade.omega * c.blade.tip_radius();
  return {c.object.mass,
          c.blade.mass(),
          c.blade.omega / units::rpm,
          c.radius,
          c.restitution.at(0),
          v0,
          v1,
          v1 / units::ft_per_min,
          tip_speed,
          c.object.mass / c.blade.mass(),
          (v1 - v0) / tip_speed};
}

std::vector<double> assessment_point(const SweepSpec& spec, const Point& p, const toml::table& base, int threads, double& required) {
  auto sc =
      prepare<scenario::Scenario>(spec, p, base, [](const toml::table& d, const std::string& f) { return scenario::read_scenario(d, f); });
  if (spec.replicates > 0) sc.run.replicates = spec.replicates;
  if (spec.seed) sc.run.seed = *spec.seed;
  const assess::Simulator sim(sc);
  const assess::Assessment a = assess::run_assessment(sim, threads);
  const assess::Summary sum = assess::summarise(a, sc);
  // A point where the test did not really happen has no P(pass) to plot.
  if (!sum.validity.valid) throw InvalidPoint(point_error(spec, p, "the simulated test is invalid here: " + sum.validity.reasons.front()));
  required = sum.required;
  std::vector<double> v{static_cast<double>(sum.replicates),
                        sum.pass.estimate,
                        sum.pass.low,
                        sum.pass.high,
                        sum.criteria[0].mean_share,
                        sum.criteria[1].mean_share,
                        sum.criteria[2].mean_share,
                        sum.criteria[3].mean_share,
                        sum.marks_per_nail};
  for (const auto& c : sum.criteria) v.insert(v.end(), {c.q05, c.q95, c.limit});
  return v;
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

// A field scenario's point: one hazard run. Its columns (the planes' and the directions'
// names) are the first point's; every point must have the same planes.
std::vector<double> hazard_point(const SweepSpec& spec, const Point& p, const toml::table& base, int threads, SweepTable& t) {
  auto sc =
      prepare<scenario::Scenario>(spec, p, base, [](const toml::table& d, const std::string& f) { return scenario::read_scenario(d, f); });
  if (spec.objects > 0) sc.field.objects_simulated = spec.objects;
  if (spec.seed) sc.run.seed = *spec.seed;
  if (!sc.field.present) throw point_error(spec, p, "the base is a field scenario at its other points; here it has no [field]");
  std::optional<field::FieldSimulator> made;
  try {
    made.emplace(sc);
  } catch (const InputError& e) {  // what the point's settings made of the field (no size can reach a blade, say)
    throw InvalidPoint(point_error(spec, p, e.what()));
  }
  const field::FieldSimulator& sim = *made;
  const field::HazardRun run = field::run_hazard(sim, threads);
  const field::HazardSummary sum = field::summarise(sim, run);
  // A run with too many objects cut off by its limits has no hazard to plot.
  if (!sum.valid) throw InvalidPoint(point_error(spec, p, "the hazard run is invalid here: " + sum.invalid_reason));
  std::vector<std::string> planes, directions;
  for (const auto& pl : sum.planes) planes.push_back(pl.plane.name);
  for (const auto& d : sum.directions) directions.push_back(d.direction);
  const bool first = std::none_of(t.rows.begin(), t.rows.end(), [](const SweepTable::Row& r) { return r.invalid.empty(); });
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
    throw point_error(spec, p, "the planes differ from the sweep's first point: every point must tally the same planes");
  }
  std::vector<double> v{static_cast<double>(sum.objects), sum.reaching_per_km, sum.thrown_per_km, sum.last_strike_speed_mean,
                        100 * sum.cut_off_share};
  for (const auto& d : sum.directions)
    v.insert(v.end(), {d.hazard_distance, d.hazard_distance_upper, d.beyond_range ? 1.0 : 0.0, d.upper_beyond_range ? 1.0 : 0.0});
  for (const auto& pl : sum.planes) v.insert(v.end(), {pl.hazardous_per_km.value, pl.hazardous_per_km.low, pl.hazardous_per_km.high});
  return v;
}

}  // namespace

const char* points_name(SweepTable::Kind kind) {
  switch (kind) {
    case SweepTable::Kind::Impact: return "impacts";
    case SweepTable::Kind::Assessment: return "J232 assessments";
    case SweepTable::Kind::Hazard: return "hazard runs";
  }
  return "points";
}

SweepTable run_sweep(const SweepSpec& spec, int threads, SweepProgress* progress) {
  const toml::table base = scenario::parse_toml_file(spec.base);
  SweepTable t;
  t.kind = base.contains("contact") ? SweepTable::Kind::Impact : base.contains("field") ? SweepTable::Kind::Hazard : SweepTable::Kind::Assessment;
  if (t.kind != SweepTable::Kind::Hazard && spec.objects > 0)
    throw InputError(spec.source, std::nullopt, "run.objects", std::to_string(spec.objects),
                     "objects per point are for a field scenario's sweep; a J232 scenario takes run.replicates");
  if (t.kind == SweepTable::Kind::Hazard && spec.replicates > 0)
    throw InputError(spec.source, std::nullopt, "run.replicates", std::to_string(spec.replicates),
                     "a field scenario's sweep takes run.objects (objects per point), not replicates");
  if (t.kind == SweepTable::Kind::Hazard)
    t.columns = {"objects", "reaching_per_km", "thrown_per_km", "last_strike_speed_m_s", "cut_off_percent"};  // then per direction and plane
  else if (t.kind == SweepTable::Kind::Assessment)
    t.columns = {"replicates",
                 "p_pass",
                 "p_pass_low",
                 "p_pass_high",
                 "share_hits_zone",
                 "share_punctures_zone",
                 "share_hits_outside",
                 "share_punctures_outside",
                 "marks_per_nail",
                 "q05_hits_zone",
                 "q95_hits_zone",
                 "limit_hits_zone",
                 "q05_punctures_zone",
                 "q95_punctures_zone",
                 "limit_punctures_zone",
                 "q05_hits_outside",
                 "q95_hits_outside",
                 "limit_hits_outside",
                 "q05_punctures_outside",
                 "q95_punctures_outside",
                 "limit_punctures_outside"};
  else
    t.columns = {"object_mass_kg",          "blade_mass_kg",          "blade_speed_rpm",           "contact_radius_m", "restitution",
                 "object_speed_before_m_s", "object_speed_after_m_s", "object_speed_after_ft_min", "tip_speed_m_s",    "mass_ratio",
                 "dimensionless_velocity"};
  const std::vector<Point> all = points(spec, t.series_labels);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Point& p = all[i];
    const Setting& x = *p.settings.back();
    SweepTable::Row row{p.series, t.series_labels[p.series], x.text, display(x), {}, {}};
    try {
      switch (t.kind) {
        case SweepTable::Kind::Impact: row.values = impact_point(spec, p, base); break;
        case SweepTable::Kind::Assessment: row.values = assessment_point(spec, p, base, threads, t.required_pass_probability); break;
        case SweepTable::Kind::Hazard: row.values = hazard_point(spec, p, base, threads, t); break;
      }
    } catch (const InvalidPoint& e) {
      if (t.kind == SweepTable::Kind::Impact) throw e.reader ? *e.reader : e.error;  // an impact is computed, not simulated: the spec is at fault
      row.invalid = e.error.what();
    }
    t.rows.push_back(std::move(row));
    if (progress) progress->point(i + 1, all.size());
  }
  // Not one point assessed: nothing to draw, and likely the sweep's own fault.
  if (std::all_of(t.rows.begin(), t.rows.end(), [](const SweepTable::Row& r) { return !r.invalid.empty(); })) {
    const auto first = std::find_if(t.rows.begin(), t.rows.end(), [](const SweepTable::Row& r) { return !r.invalid.empty(); });
    if (first != t.rows.end())
      throw InputError(spec.source, std::nullopt, "sweep", spec.name, "no point could be assessed; the first: " + first->invalid);
  }
  return t;
}

std::size_t column(const SweepTable& t, const std::string& name) {
  for (std::size_t i = 0; i < t.columns.size(); ++i)
    if (t.columns[i] == name) return i;
  throw std::out_of_range("no column " + name);
}

}  // namespace j232::study
