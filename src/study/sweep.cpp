// Running a sweep: every point, each an impact or a whole assessment (study/sweep.hpp).
#include "study/sweep.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <optional>
#include <stdexcept>

#include "blade/blade_model.hpp"
#include "pipeline/pipeline.hpp"
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

// A J232 or field scenario's point: one run of the base's pipeline (pipeline/pipeline.hpp),
// which fills the table's columns.
std::vector<double> pipeline_point(const SweepSpec& spec, const Point& p, const toml::table& base, const pipeline::Pipeline& pipeline,
                                   int threads, SweepTable& t) {
  auto sc =
      prepare<scenario::Scenario>(spec, p, base, [](const toml::table& d, const std::string& f) { return scenario::read_scenario(d, f); });
  if (spec.seed) sc.run.seed = *spec.seed;
  const bool first = std::none_of(t.rows.begin(), t.rows.end(), [](const SweepTable::Row& r) { return r.invalid.empty(); });
  pipeline::SweepColumns columns{std::move(t.columns), std::move(t.planes), std::move(t.directions), t.required_pass_probability};
  std::string invalid;
  std::vector<double> v;
  try {
    v = pipeline.sweep_point(sc, {spec.replicates, spec.objects}, first, threads, columns, invalid);
  } catch (const pipeline::BrokenSweep& e) {
    throw point_error(spec, p, e.what());
  }
  t.columns = std::move(columns.columns), t.planes = std::move(columns.planes), t.directions = std::move(columns.directions);
  t.required_pass_probability = columns.required_pass_probability;
  if (!invalid.empty()) throw InvalidPoint(point_error(spec, p, invalid));
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
  const bool impact = base.contains("contact");
  const pipeline::Pipeline& pipeline = pipeline::pipeline_of(base);
  t.kind = impact ? SweepTable::Kind::Impact : pipeline.kind() == pipeline::Pipeline::Kind::Field ? SweepTable::Kind::Hazard : SweepTable::Kind::Assessment;
  if (impact)
    t.columns = {"object_mass_kg",          "blade_mass_kg",          "blade_speed_rpm",           "contact_radius_m", "restitution",
                 "object_speed_before_m_s", "object_speed_after_m_s", "object_speed_after_ft_min", "tip_speed_m_s",    "mass_ratio",
                 "dimensionless_velocity"};
  else
    t.columns = pipeline.sweep_columns();
  if (const auto refused = pipeline.refuse_sweep_size({spec.replicates, spec.objects}))
    throw InputError(spec.source, std::nullopt, refused->key, refused->value, refused->why);
  const std::vector<Point> all = points(spec, t.series_labels);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Point& p = all[i];
    const Setting& x = *p.settings.back();
    SweepTable::Row row{p.series, t.series_labels[p.series], x.text, display(x), {}, {}};
    try {
      switch (t.kind) {
        case SweepTable::Kind::Impact: row.values = impact_point(spec, p, base); break;
        case SweepTable::Kind::Assessment:
        case SweepTable::Kind::Hazard: row.values = pipeline_point(spec, p, base, pipeline, threads, t); break;
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
