#include "report/sweep_report.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "assess/tally.hpp"
#include "report/svg_chart.hpp"

namespace j232::report {

using study::column;
using study::SweepSpec;
using study::SweepTable;
using study::Parameter;

std::string sweep_csv(const SweepSpec& spec, const SweepTable& t) {
  // A point not assessed has empty values and, in a last `note` column (there only when some
  // point was not assessed), why.
  const bool notes = t.any_invalid();
  std::string o = fmt::format("series,{},{}", spec.x.info.name, spec.x.info.name + "_value");
  for (const auto& c : t.columns) o += "," + c;
  o += notes ? ",note\n" : "\n";
  for (const auto& r : t.rows) {
    o += fmt::format("\"{}\",\"{}\",{:.8g}", r.series_label, r.x_text, r.x);
    if (r.invalid.empty())
      for (double v : r.values) o += fmt::format(",{:.8g}", v);
    else
      o += std::string(t.columns.size(), ',');
    if (notes) {
      std::string quoted;
      for (char ch : r.invalid) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
      o += r.invalid.empty() ? "," : ",\"" + quoted + "\"";
    }
    o += "\n";
  }
  return o;
}

namespace {
// The points a chart leaves out (not assessed), for its caption; empty when it draws them all.
std::string left_out(const SweepSpec& spec, const SweepTable& t) {
  std::string o;
  for (const auto& r : t.rows)
    if (!r.invalid.empty())
      o += fmt::format("{}{}{}{}", o.empty() ? "" : "; ", r.series_label.empty() ? "" : r.series_label + ", ", spec.x.info.name + " = ", r.x_text);
  return o.empty() ? o : " Not assessed, so not drawn (the CSV's note says why): " + o + ".";
}
// A series' points in runs between the points not assessed: a line is not drawn across a gap.
std::vector<std::vector<const SweepTable::Row*>> series_runs(const SweepTable& t, std::size_t s) {
  std::vector<std::vector<const SweepTable::Row*>> runs(1);
  for (const auto& r : t.rows) {
    if (r.series != s) continue;
    if (!r.invalid.empty()) {
      if (!runs.back().empty()) runs.emplace_back();
      continue;
    }
    runs.back().push_back(&r);
  }
  if (runs.size() > 1 && runs.back().empty()) runs.pop_back();
  return runs;
}
// The first point assessed (the sweep has one: run_sweep refuses a sweep with none).
const SweepTable::Row& first_assessed(const SweepTable& t) {
  for (const auto& r : t.rows)
    if (r.invalid.empty()) return r;
  return t.rows.front();
}
}  // namespace

namespace {
// A field's sweep: each plane's hazardous crossings per km (log axis, 95 % intervals), the
// hazard distance each way, and the objects thrown per km.
std::vector<std::pair<std::string, std::string>> hazard_sweep_charts(const SweepSpec& spec, const SweepTable& t) {
  std::vector<std::pair<std::string, std::string>> out;
  const std::size_t n_series = t.series_labels.size();

  const std::string objects = t.rows.empty() ? "0" : fmt::format("{:.0f}", first_assessed(t).values[column(t, "objects")]);
  // Each plane's three columns (plane_NAME_hazardous_per_km, _low, _high), in the planes' order.
  std::vector<std::size_t> plane_columns;
  const std::string suffix = "_hazardous_per_km";
  for (std::size_t k = 0; k < t.columns.size(); ++k)
    if (t.columns[k].rfind("plane_", 0) == 0 && t.columns[k].size() > suffix.size() &&
        t.columns[k].compare(t.columns[k].size() - suffix.size(), suffix.size(), suffix) == 0)
      plane_columns.push_back(k);
  for (std::size_t i = 0; i < t.planes.size() && i < plane_columns.size(); ++i) {
    const std::size_t v = plane_columns[i], lo = v + 1, hi = v + 2;
    report::Chart c(fmt::format("{}: plane '{}'", spec.title, t.planes[i]), spec.x.info.axis_title, "hazardous crossings per km mowed");
    double highest = 0, lowest = HUGE_VAL;
    for (std::size_t s = 0; s < n_series; ++s) {
      bool first_run = true;
      for (const auto& run : series_runs(t, s)) {
        std::vector<double> x, y, yl, yh;
        for (const auto* r : run) {
          x.push_back(r->x), y.push_back(r->values[v]), yl.push_back(r->values[lo]), yh.push_back(r->values[hi]);
          for (double w : {r->values[v], r->values[lo], r->values[hi]})
            if (w > 0) highest = std::max(highest, w), lowest = std::min(lowest, w);
        }
        c.error_bars(x, yl, yh, report::palette(s));
        c.line(x, y, report::palette(s), !first_run ? "" : t.series_labels[s].empty() ? "hazardous per km" : t.series_labels[s]);
        first_run = false;
      }
    }
    if (highest > 0) {
      const double top = std::pow(10.0, std::ceil(std::log10(highest) - 1e-9));
      c.y_log_range(std::max(top * 1e-10, std::pow(10.0, std::floor(std::log10(lowest) + 1e-9))), top);
    }
    c.caption(fmt::format("Bars: 95 % intervals (Fay and Feuer's, for the strata's weighted counts), {} objects per point; a "
                          "zero is drawn on the axis's floor.{}",
                          objects, left_out(spec, t)));
    out.emplace_back(fmt::format("plane-{}", i + 1), c.svg());
  }
  // The hazard distance, a chart per direction: a colour per series, the estimate solid with
  // markers and the conservative distance dashed in the same colour.
  for (std::size_t k = 0; k < t.directions.size(); ++k) {
    report::Chart d(fmt::format("{}: hazard distance, {}", spec.title, t.directions[k]), spec.x.info.axis_title, "hazard distance (m)");
    const std::size_t est = column(t, t.directions[k] + "_hazard_distance_m"), up = column(t, t.directions[k] + "_hazard_distance_upper_m");
    double farthest = 0;
    for (std::size_t s = 0; s < n_series; ++s) {
      bool first_run = true;
      for (const auto& run : series_runs(t, s)) {
        std::vector<double> x, y, yu;
        for (const auto* r : run) {
          x.push_back(r->x), y.push_back(r->values[est]), yu.push_back(r->values[up]);
          farthest = std::max({farthest, r->values[est], r->values[up]});
        }
        d.line(x, y, report::palette(s), !first_run ? "" : t.series_labels[s].empty() ? "estimate" : t.series_labels[s], true, false);
        d.line(x, yu, report::palette(s), !first_run || !t.series_labels[s].empty() ? "" : "conservative", false, true);
        first_run = false;
      }
    }
    d.y_range(0, 1.1 * farthest + 1e-9);
    d.caption("Solid with markers: the estimate; dashed: the conservative distance (on the density's 95 % upper bound). At the deck's "
              "edge where hazardous impacts stay below the acceptable density everywhere beyond it; the CSV flags a distance beyond "
              "the range." + left_out(spec, t));
    out.emplace_back("hazard-distance-" + t.directions[k], d.svg());
  }
  report::Chart th(spec.title + ": objects thrown", spec.x.info.axis_title, "objects thrown per km mowed");
  for (std::size_t s = 0; s < n_series; ++s) {
    bool first_run = true;
    for (const auto& run : series_runs(t, s)) {
      std::vector<double> x, y;
      for (const auto* r : run) x.push_back(r->x), y.push_back(r->values[column(t, "thrown_per_km")]);
      th.line(x, y, report::palette(s), !first_run ? "" : t.series_labels[s].empty() ? "thrown per km" : t.series_labels[s]);
      first_run = false;
    }
  }
  th.caption("Objects the blades threw per km mowed (every kind)." + left_out(spec, t));
  out.emplace_back("thrown", th.svg());
  return out;
}
}  // namespace

std::vector<std::pair<std::string, std::string>> sweep_charts(const SweepSpec& spec, const SweepTable& t) {
  std::vector<std::pair<std::string, std::string>> out;
  const std::size_t n_series = t.series_labels.size();
  auto series_rows = [&](std::size_t s) {
    std::vector<const SweepTable::Row*> rows;
    for (const auto& r : t.rows)
      if (r.series == s && r.invalid.empty()) rows.push_back(&r);
    return rows;
  };
  if (t.kind == SweepTable::Kind::Hazard) return hazard_sweep_charts(spec, t);
  if (t.kind == SweepTable::Kind::Assessment) {
    report::Chart chart(spec.title, spec.x.info.axis_title, "P(pass one J232 test)");
    const std::size_t p = column(t, "p_pass"), lo = column(t, "p_pass_low"), hi = column(t, "p_pass_high");
    for (std::size_t s = 0; s < n_series; ++s) {
      bool first_run = true;
      for (const auto& run : series_runs(t, s)) {
        std::vector<double> x, y, yl, yh;
        for (const auto* r : run) x.push_back(r->x), y.push_back(r->values[p]), yl.push_back(r->values[lo]), yh.push_back(r->values[hi]);
        const std::string label = !first_run ? "" : t.series_labels[s].empty() ? "P(pass)" : t.series_labels[s];
        chart.band(x, yl, yh, report::palette(s), "");
        chart.error_bars(x, yl, yh, report::palette(s));
        chart.line(x, y, report::palette(s), label);
        first_run = false;
      }
    }
    chart.hline(t.required_pass_probability, "#c62828", fmt::format("required {:g}", t.required_pass_probability));
    chart.y_range(0, 1.05);
    chart.caption(fmt::format("Bands and bars: Wilson 95 % intervals, {} replicates per point.{}",
                              t.rows.empty() ? 0 : static_cast<long long>(first_assessed(t).values[0]), left_out(spec, t)));
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
        bool first_run = true;
        for (const auto& run : series_runs(t, s)) {
          std::vector<double> x, y, yl, yh;
          for (const auto* r : run) {
            x.push_back(r->x), y.push_back(100 * r->values[mean]), yl.push_back(100 * r->values[q05]), yh.push_back(100 * r->values[q95]);
            top = std::max(top, 100 * r->values[q95]);
          }
          const std::string label = !first_run ? "" : t.series_labels[s].empty() ? "mean share" : t.series_labels[s];
          c.band(x, yl, yh, report::palette(s), "");
          c.line(x, y, report::palette(s), label);
          first_run = false;
        }
      }
      const double lim = t.rows.empty() ? 0 : 100 * first_assessed(t).values[limit];
      c.hline(lim, "#c62828", fmt::format("limit {:g} %", lim));
      c.y_range(0, 1.1 * std::max(top, lim) + 1e-9);
      c.caption(
          "Line: mean share over the replicates; band: 5-95 % range of the share in single "
          "tests; dashed: the criterion's limit." + left_out(spec, t));
      out.emplace_back("share-" + name, c.svg());
    }
    return out;
  }
  const std::size_t speed = column(t, "object_speed_after_m_s"), ratio = column(t, "mass_ratio"),
                    dimless = column(t, "dimensionless_velocity");
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
  nondim.caption(
      "v0: the object's speed toward the blade before impact; tip speed: omega times the tip radius (report 445-1 Figs 2.8-2.11, 2.16).");
  out.emplace_back("dimensional", dim.svg());
  out.emplace_back("dimensionless", nondim.svg());
  return out;
}

}  // namespace j232::report
