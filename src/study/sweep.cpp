#include "study/sweep.hpp"

#include <filesystem>
#include <fmt/format.h>
#include <set>
#include <stdexcept>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "assess/tally.hpp"
#include "blade/blade_model.hpp"
#include "report/svg_chart.hpp"
#include "scenario/input_error.hpp"
#include "scenario/toml_reader.hpp"
#include "scenario/scenario_reader.hpp"

namespace j232::study {

namespace {

using scenario::InputError;

std::optional<int> line_of(const toml::node& n) {
  return n.source().begin.line > 0 ? std::optional<int>(static_cast<int>(n.source().begin.line)) : std::nullopt;
}

std::string value_text(const toml::node& n) {
  if (auto s = n.value<std::string>()) return *s;
  if (n.is_integer()) return fmt::format("{}", *n.value<long long>());
  if (n.is_floating_point()) return fmt::format("{}", *n.value<double>());
  if (auto b = n.value<bool>()) return *b ? "true" : "false";
  return "";
}

void refuse_unknown(const toml::table& t, const std::set<std::string>& known, const std::string& file, const std::string& path) {
  for (const auto& [k, v] : t)
    if (!known.count(std::string(k.str())))
      throw InputError(file, line_of(v), path + std::string(k.str()), value_text(v),
                       fmt::format("unknown key; this table takes: {}", fmt::join(known, ", ")));
}

Axis read_axis(const toml::table& t, const std::string& file, const std::string& path) {
  refuse_unknown(t, {"parameter", "values", "from", "to", "steps"}, file, path);
  const auto* p = t.get("parameter");
  if (!p || !p->is_string())
    throw InputError(file, line_of(t), path + "parameter", "",
                     "missing; expected a parameter name (blade_speed, blade_mass, restitution, contact_radius, "
                     "pivot_position, object_mass, object_speed) or a dotted key of the base file");
  Axis axis{parameter_info(*p->value<std::string>()), {}};
  if (const auto* values = t.get_as<toml::array>("values")) {
    if (t.contains("from")) throw InputError(file, line_of(t), path + "from", "", "expected either values or from/to/steps, not both");
    for (const auto& v : *values) {
      const std::string text = value_text(v);
      if (text.empty()) throw InputError(file, line_of(v), path + "values", "", "expected numbers or quantities such as \"700 rpm\"");
      axis.values.push_back(make_setting(axis.info, text, file, line_of(v), path + "values"));
    }
  } else if (t.contains("from") || t.contains("to")) {
    const std::string from = t.contains("from") ? value_text(*t.get("from")) : "", to = t.contains("to") ? value_text(*t.get("to")) : "";
    const auto* steps_node = t.get("steps");
    const long long steps = steps_node ? steps_node->value<long long>().value_or(0) : 0;
    if (steps < 2 || steps > 1000)
      throw InputError(file, steps_node ? line_of(*steps_node) : line_of(t), path + "steps", steps_node ? value_text(*steps_node) : "",
                       "expected an integer number of points from 2 to 1000");
    const Setting a = make_setting(axis.info, from, file, line_of(*t.get("from")), path + "from");
    const Setting b = make_setting(axis.info, to, file, line_of(*t.get("to")), path + "to");
    // Points evenly spaced, written in the unit `from` was written in.
    const auto space = from.find(' ');
    const std::string unit = space == std::string::npos ? "" : from.substr(space);
    const double per_unit = a.si / std::stod(from);
    for (long long i = 0; i < steps; ++i) {
      const double si = a.si + (b.si - a.si) * static_cast<double>(i) / static_cast<double>(steps - 1);
      axis.values.push_back(make_setting(axis.info, fmt::format("{:.6g}{}", si / per_unit, unit), file, line_of(t), path + "from"));
      axis.values.back().si = si;  // exact, not as rounded for the label
    }
  } else {
    throw InputError(file, line_of(t), path + "values", "", "missing; expected values = [...] or from, to and steps");
  }
  if (axis.values.empty()) throw InputError(file, line_of(t), path + "values", "[]", "expected at least one value");
  axis.info = axis.values.front().info;  // a file key's axis title names the unit its values were given in
  return axis;
}

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

// The base with a point's settings: file keys into the document, which is then read
// (with all the reader's checks), then the named parameters onto what was read.
template <class Input, class Read>
Input prepare(const SweepSpec& spec, const Point& p, const toml::table& base, Read read) {
  toml::table doc = base;
  for (const auto* s : p.settings) apply_to_document(*s, doc, spec.source);
  Input input = read(doc, spec.base);
  try {
    for (const auto* s : p.settings) apply(*s, input);
  } catch (const std::invalid_argument& e) {
    throw point_error(spec, p, e.what());
  }
  return input;
}

std::vector<double> impact_point(const SweepSpec& spec, const Point& p, const toml::table& base) {
  const auto c = prepare<scenario::ImpactCase>(spec, p, base, scenario::read_impact_case);
  const auto where = blade::locate(c.blade, c.arm, c.radius);
  if (!where)
    throw point_error(spec, p, fmt::format("the contact radius {:.4g} m is off the blade (tip radius {:.4g} m)", c.radius, c.blade.tip_radius()));
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
  auto sc = prepare<scenario::Scenario>(spec, p, base, [](const toml::table& d, const std::string& f) { return scenario::read_scenario(d, f); });
  if (spec.replicates > 0) sc.run.replicates = spec.replicates;
  if (spec.seed) sc.run.seed = *spec.seed;
  const assess::Simulator sim(sc);
  const assess::Assessment a = assess::run_assessment(sim, threads);
  const assess::Summary sum = assess::summarise(a, sc);
  // A point where the test did not really happen has no P(pass) to plot.
  if (!sum.validity.valid) throw point_error(spec, p, "the simulated test is invalid here: " + sum.validity.reasons.front());
  required = sum.required;
  std::vector<double> v{static_cast<double>(sum.replicates), sum.pass.estimate, sum.pass.low, sum.pass.high,
                        sum.criteria[0].mean_share, sum.criteria[1].mean_share, sum.criteria[2].mean_share, sum.criteria[3].mean_share,
                        sum.marks_per_nail};
  for (const auto& c : sum.criteria) v.insert(v.end(), {c.q05, c.q95, c.limit});
  return v;
}

}  // namespace

SweepSpec read_sweep_file(const std::string& file) {
  const toml::table doc = scenario::parse_toml_file(file);
  refuse_unknown(doc, {"title", "base", "set", "x", "series", "run"}, file, "");
  SweepSpec spec;
  spec.source = file;
  spec.name = std::filesystem::path(file).stem().string();
  spec.title = doc["title"].value_or(spec.name);
  const auto base = doc["base"].value<std::string>();
  if (!base) throw InputError(file, line_of(doc), "base", "", "missing; expected the impact case or J232 scenario to vary, relative to this file");
  spec.base = (std::filesystem::path(file).parent_path() / *base).lexically_normal().string();
  if (const auto* set = doc.get("set")) {
    if (!set->is_table()) throw InputError(file, line_of(*set), "set", "", "expected a [set] table of parameter = value");
    for (const auto& [k, v] : *set->as_table()) {
      const std::string text = value_text(v);
      if (text.empty()) throw InputError(file, line_of(v), "set." + std::string(k.str()), "", "expected a number or quantity");
      spec.fixed.push_back(make_setting(parameter_info(std::string(k.str())), text, file, line_of(v), "set." + std::string(k.str())));
    }
  }
  const auto* x = doc.get_as<toml::table>("x");
  if (!x) throw InputError(file, line_of(doc), "x", "", "missing; expected an [x] table: parameter and values");
  spec.x = read_axis(*x, file, "x.");
  if (const auto* series = doc.get("series")) {
    const auto* list = series->as_array();
    if (!list || !list->is_array_of_tables())
      throw InputError(file, line_of(*series), "series", "", "expected [[series]] tables: parameter and values");
    for (std::size_t i = 0; i < list->size(); ++i)
      spec.series.push_back(read_axis(*list->get(i)->as_table(), file, fmt::format("series[{}].", i + 1)));
  }
  if (const auto* run = doc.get_as<toml::table>("run")) {
    refuse_unknown(*run, {"replicates", "seed"}, file, "run.");
    if (const auto* r = run->get("replicates")) {
      spec.replicates = r->value<long long>().value_or(0);
      if (spec.replicates <= 0) throw InputError(file, line_of(*r), "run.replicates", value_text(*r), "expected a positive integer");
    }
    if (const auto* s = run->get("seed")) {
      const long long seed = s->value<long long>().value_or(-1);
      if (seed < 0) throw InputError(file, line_of(*s), "run.seed", value_text(*s), "expected a non-negative integer");
      spec.seed = static_cast<unsigned long long>(seed);
    }
  }
  return spec;
}

Axis parse_axis(const std::string& text, const std::string& option) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InputError("", std::nullopt, option, text, "expected PARAMETER=V1,V2,... for example blade_speed=\"700 rpm,800 rpm\"");
  Axis axis{parameter_info(text.substr(0, eq)), {}};
  std::size_t start = eq + 1;
  while (start <= text.size()) {
    std::size_t comma = text.find(',', start);
    if (comma == std::string::npos) comma = text.size();
    std::string v = text.substr(start, comma - start);
    v.erase(0, v.find_first_not_of(' '));
    v.erase(v.find_last_not_of(' ') + 1);
    if (!v.empty()) axis.values.push_back(make_setting(axis.info, v, "", std::nullopt, option));
    start = comma + 1;
  }
  if (axis.values.empty()) throw InputError("", std::nullopt, option, text, "expected at least one value");
  axis.info = axis.values.front().info;
  return axis;
}

SweepTable run_sweep(const SweepSpec& spec, int threads, SweepProgress* progress) {
  const toml::table base = scenario::parse_toml_file(spec.base);
  SweepTable t;
  t.assessment = !base.contains("contact");
  if (t.assessment)
    t.columns = {"replicates", "p_pass", "p_pass_low", "p_pass_high", "share_hits_zone", "share_punctures_zone",
                 "share_hits_outside", "share_punctures_outside", "marks_per_nail",
                 "q05_hits_zone", "q95_hits_zone", "limit_hits_zone", "q05_punctures_zone", "q95_punctures_zone",
                 "limit_punctures_zone", "q05_hits_outside", "q95_hits_outside", "limit_hits_outside",
                 "q05_punctures_outside", "q95_punctures_outside", "limit_punctures_outside"};
  else
    t.columns = {"object_mass_kg", "blade_mass_kg", "blade_speed_rpm", "contact_radius_m", "restitution",
                 "object_speed_before_m_s", "object_speed_after_m_s", "object_speed_after_ft_min", "tip_speed_m_s",
                 "mass_ratio", "dimensionless_velocity"};
  const std::vector<Point> all = points(spec, t.series_labels);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Point& p = all[i];
    const Setting& x = *p.settings.back();
    SweepTable::Row row{p.series, t.series_labels[p.series], x.text, display(x), {}};
    row.values = t.assessment ? assessment_point(spec, p, base, threads, t.required_pass_probability) : impact_point(spec, p, base);
    t.rows.push_back(std::move(row));
    if (progress) progress->point(i + 1, all.size());
  }
  return t;
}

std::size_t column(const SweepTable& t, const std::string& name) {
  for (std::size_t i = 0; i < t.columns.size(); ++i)
    if (t.columns[i] == name) return i;
  throw std::out_of_range("no column " + name);
}

std::string sweep_csv(const SweepSpec& spec, const SweepTable& t) {
  std::string o = fmt::format("series,{},{}", spec.x.info.name, spec.x.info.name + "_value");
  for (const auto& c : t.columns) o += "," + c;
  o += "\n";
  for (const auto& r : t.rows) {
    o += fmt::format("\"{}\",\"{}\",{:.8g}", r.series_label, r.x_text, r.x);
    for (double v : r.values) o += fmt::format(",{:.8g}", v);
    o += "\n";
  }
  return o;
}

std::vector<std::pair<std::string, std::string>> sweep_charts(const SweepSpec& spec, const SweepTable& t) {
  std::vector<std::pair<std::string, std::string>> out;
  const std::size_t n_series = t.series_labels.size();
  auto series_rows = [&](std::size_t s) {
    std::vector<const SweepTable::Row*> rows;
    for (const auto& r : t.rows)
      if (r.series == s) rows.push_back(&r);
    return rows;
  };
  if (t.assessment) {
    report::Chart chart(spec.title, spec.x.info.axis_title, "P(pass one J232 test)");
    const std::size_t p = column(t, "p_pass"), lo = column(t, "p_pass_low"), hi = column(t, "p_pass_high");
    for (std::size_t s = 0; s < n_series; ++s) {
      std::vector<double> x, y, yl, yh;
      for (const auto* r : series_rows(s)) x.push_back(r->x), y.push_back(r->values[p]), yl.push_back(r->values[lo]), yh.push_back(r->values[hi]);
      const std::string label = t.series_labels[s].empty() ? "P(pass)" : t.series_labels[s];
      chart.band(x, yl, yh, report::palette(s), "");
      chart.error_bars(x, yl, yh, report::palette(s));
      chart.line(x, y, report::palette(s), label);
    }
    chart.hline(t.required_pass_probability, "#c62828", fmt::format("required {:g}", t.required_pass_probability));
    chart.y_range(0, 1.05);
    chart.caption(fmt::format("Bands and bars: Wilson 95 % intervals, {} replicates per point.",
                              t.rows.empty() ? 0 : static_cast<long long>(t.rows.front().values[0])));
    out.emplace_back("pass-probability", chart.svg());
    // Each criterion's share per point: the mean and the 5-95 % range of single tests, and
    // its limit, so the margin to the limit shows, not only P(pass)'s jump.
    static const char* words[] = {"hits in the operator zone", "punctures in the operator zone", "hits outside the zone",
                                  "punctures outside the zone"};
    for (int k = 0; k < 4; ++k) {
      const std::string name = assess::category_name(k);
      const std::size_t mean = column(t, "share_" + name), q05 = column(t, "q05_" + name), q95 = column(t, "q95_" + name),
                        limit = column(t, "limit_" + name);
      report::Chart c(fmt::format("{}: {}", spec.title, words[k]), spec.x.info.axis_title, "share of the nails fed (%)");
      double top = 0;
      for (std::size_t s = 0; s < n_series; ++s) {
        std::vector<double> x, y, yl, yh;
        for (const auto* r : series_rows(s)) {
          x.push_back(r->x), y.push_back(100 * r->values[mean]), yl.push_back(100 * r->values[q05]), yh.push_back(100 * r->values[q95]);
          top = std::max(top, 100 * r->values[q95]);
        }
        const std::string label = t.series_labels[s].empty() ? "mean share" : t.series_labels[s];
        c.band(x, yl, yh, report::palette(s), "");
        c.line(x, y, report::palette(s), label);
      }
      const double lim = t.rows.empty() ? 0 : 100 * t.rows.front().values[limit];
      c.hline(lim, "#c62828", fmt::format("limit {:g} %", lim));
      c.y_range(0, 1.1 * std::max(top, lim) + 1e-9);
      c.caption("Line: mean share over the replicates; band: 5-95 % range of the share in single "
                "tests; dashed: the criterion's limit.");
      out.emplace_back("share-" + name, c.svg());
    }
    return out;
  }
  const std::size_t speed = column(t, "object_speed_after_m_s"), ratio = column(t, "mass_ratio"), dimless = column(t, "dimensionless_velocity");
  const bool x_is_object_mass = spec.x.info.parameter == Parameter::ObjectMass;
  report::Chart dim(spec.title, spec.x.info.axis_title, "object speed after impact (m/s)");
  report::Chart nondim(spec.title + " (dimensionless)", x_is_object_mass ? "object mass / blade mass" : spec.x.info.axis_title,
                       "(v' - v0) / (tip speed)");
  for (std::size_t s = 0; s < n_series; ++s) {
    std::vector<double> x, xd, y, yd;
    for (const auto* r : series_rows(s)) {
      x.push_back(r->x), y.push_back(r->values[speed]);
      xd.push_back(x_is_object_mass ? r->values[ratio] : r->x), yd.push_back(r->values[dimless]);
    }
    const std::string label = t.series_labels[s];
    dim.line(x, y, report::palette(s), label, true, s >= 8);
    nondim.line(xd, yd, report::palette(s), label, true, s >= 8);
  }
  dim.caption("v': the object's speed after impact along the blade's motion. Computed by j232's impact core.");
  nondim.caption("v0: the object's speed toward the blade before impact; tip speed: omega times the tip radius (report 445-1 Figs 2.8-2.11, 2.16).");
  out.emplace_back("dimensional", dim.svg());
  out.emplace_back("dimensionless", nondim.svg());
  return out;
}

}  // namespace j232::study
