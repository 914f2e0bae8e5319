#include "report/comparison_report.hpp"

#include <fmt/format.h>

#include "assess/tally.hpp"
#include "report/html_page.hpp"
#include "report/svg_chart.hpp"
#include "report/text_safety.hpp"

namespace j232::report {

namespace {
using json = nlohmann::ordered_json;
const char* kCriterionWords[] = {"hits in the operator zone", "punctures in the operator zone", "hits outside the zone",
                                 "punctures outside the zone"};

json interval(const study::MeanInterval& m) { return {{"mean", m.mean}, {"low", m.low}, {"high", m.high}}; }
}  // namespace

json comparison_json(const study::Comparison& c) {
  json designs = json::array();
  for (const auto& d : c.designs) {
    json criteria = json::array();
    for (int k = 0; k < 4; ++k)
      criteria.push_back({{"name", assess::category_name(k)},
                          {"limit", d.limits[static_cast<std::size_t>(k)]},
                          {"share", interval(d.shares[static_cast<std::size_t>(k)])}});
    designs.push_back({{"scenario", d.file},
                       {"title", d.title},
                       {"pass_probability", {{"estimate", d.pass.estimate}, {"low", d.pass.low}, {"high", d.pass.high}}},
                       {"criteria", criteria},
                       {"marks", d.marks},
                       {"nails", d.nails}});
  }
  json diffs = json::array();
  for (std::size_t i = 0; i < c.versus_first.size(); ++i) {
    const auto& v = c.versus_first[i];
    json criteria = json::array();
    for (int k = 0; k < 4; ++k)
      criteria.push_back({{"name", assess::category_name(k)},
                          {"difference", interval(v.shares[static_cast<std::size_t>(k)])},
                          {"independent_runs_half_width", v.independent_half_width[static_cast<std::size_t>(k)]}});
    diffs.push_back({{"design", i + 2},
                     {"minus_design", 1},
                     {"pass_probability", interval(v.pass)},
                     {"independent_runs_pass_half_width", v.independent_pass_half_width},
                     {"criteria", criteria}});
  }
  return {{"program", "j232 compare"},
          {"method",
           "common random numbers: every design run with the same seed and replicates; differences judged "
           "replicate by replicate (paired), 95 % intervals mean +/- 1.96 s/sqrt(n); P(pass) per design by Wilson"},
          {"replicates", c.replicates},
          {"seed", c.seed},
          {"designs", designs},
          {"differences", diffs}};
}

std::string comparison_csv(const study::Comparison& c) {
  std::string out =
      "criterion,design,scenario,limit,share,share_low,share_high,minus_design_1,difference_low,difference_high,"
      "independent_runs_half_width\n";
  for (int k = 0; k < 4; ++k)
    for (std::size_t d = 0; d < c.designs.size(); ++d) {
      const auto& x = c.designs[d];
      const auto& s = x.shares[static_cast<std::size_t>(k)];
      out += fmt::format("{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},", assess::category_name(k), d + 1, csv_text_cell(x.file),
                         x.limits[static_cast<std::size_t>(k)], s.mean, s.low, s.high);
      if (d == 0) {
        out += ",,,\n";
        continue;
      }
      const auto& v = c.versus_first[d - 1];
      const auto& m = v.shares[static_cast<std::size_t>(k)];
      out += fmt::format("{:.6g},{:.6g},{:.6g},{:.6g}\n", m.mean, m.low, m.high, v.independent_half_width[static_cast<std::size_t>(k)]);
    }
  return out;
}

std::string comparison_html(const json& c) {
  return page_head("j232 comparison of designs") + "<h1>Comparison of designs</h1>\n" + comparison_body_html(c, "") + page_foot();
}

std::string comparison_body_html(const json& c, const std::string& prefix) {
  const auto& designs = c["designs"];
  auto number = [&](const std::string& key, const json& value, const char* format, double scale = 1.0) {
    return report::number(prefix + key, value, format, scale);
  };
  std::string o = "<ol>\n";
  for (const auto& d : designs)
    o += fmt::format("<li>{} ({})</li>\n", escape(d["title"].get<std::string>()), escape(d["scenario"].get<std::string>()));
  o += fmt::format(
      "</ol>\n<p>{} replicates of the whole test each, seed {}, with common random numbers: replicate r of "
      "every design drops its nails from the same random feed, so the differences below are judged replicate "
      "by replicate and their intervals are far tighter than those of independent runs (shown for "
      "comparison).</p>\n",
      number("replicates", c["replicates"], "{}"), number("seed", c["seed"], "{}"));
  // P(pass)
  o += "<h2>P(pass one test)</h2>\n<table class=\"numbers\"><thead><tr><th>design</th><th>P(pass)</th><th>95 % interval</th>"
       "<th>minus design 1</th><th>95 % interval</th><th>independent runs: &plusmn;</th></tr></thead><tbody>\n";
  for (std::size_t d = 0; d < designs.size(); ++d) {
    const std::string key = fmt::format("designs.{}.pass_probability", d);
    const auto& p = designs[d]["pass_probability"];
    o += fmt::format("<tr><td>{}</td><td>{}</td><td>{} to {}</td>", d + 1, number(key + ".estimate", p["estimate"], "{:.3f}"),
                     number(key + ".low", p["low"], "{:.3f}"), number(key + ".high", p["high"], "{:.3f}"));
    if (d == 0) {
      o += "<td>&mdash;</td><td></td><td></td></tr>\n";
      continue;
    }
    const std::string dk = fmt::format("differences.{}", d - 1);
    const auto& v = c["differences"][d - 1];
    o += fmt::format("<td>{}</td><td>{} to {}</td><td>{}</td></tr>\n",
                     number(dk + ".pass_probability.mean", v["pass_probability"]["mean"], "{:+.3f}"),
                     number(dk + ".pass_probability.low", v["pass_probability"]["low"], "{:+.3f}"),
                     number(dk + ".pass_probability.high", v["pass_probability"]["high"], "{:+.3f}"),
                     number(dk + ".independent_runs_pass_half_width", v["independent_runs_pass_half_width"], "{:.3f}"));
  }
  o += "</tbody></table>\n";
  // Each criterion: a table row per design and a chart with the limit.
  for (int k = 0; k < 4; ++k) {
    o += fmt::format(
        "<h2>{}</h2>\n<table class=\"numbers\"><thead><tr><th>design</th><th>mean share</th><th>95 % interval</th>"
        "<th>minus design 1</th><th>95 % interval</th><th>independent runs: &plusmn;</th></tr></thead><tbody>\n",
        kCriterionWords[k]);
    Chart chart(fmt::format("{}: each design's mean share and its 95 % interval", kCriterionWords[k]), "design",
                "mean share of the nails fed (%)", 640, 300);
    std::vector<double> x, y, lo, hi;
    for (std::size_t d = 0; d < designs.size(); ++d) {
      const std::string key = fmt::format("designs.{}.criteria.{}.share", d, k);
      const auto& s = designs[d]["criteria"][k]["share"];
      x.push_back(static_cast<double>(d + 1));
      y.push_back(100 * s["mean"].get<double>());
      lo.push_back(100 * s["low"].get<double>());
      hi.push_back(100 * s["high"].get<double>());
      o += fmt::format("<tr><td>{}</td><td>{} %</td><td>{} to {} %</td>", d + 1, number(key + ".mean", s["mean"], "{:.3f}", 100),
                       number(key + ".low", s["low"], "{:.3f}", 100), number(key + ".high", s["high"], "{:.3f}", 100));
      if (d == 0) {
        o += "<td>&mdash;</td><td></td><td></td></tr>\n";
        continue;
      }
      const std::string dk = fmt::format("differences.{}.criteria.{}", d - 1, k);
      const auto& v = c["differences"][d - 1]["criteria"][k];
      o += fmt::format("<td>{} %</td><td>{} to {} %</td><td>{} %</td></tr>\n",
                       number(dk + ".difference.mean", v["difference"]["mean"], "{:+.3f}", 100),
                       number(dk + ".difference.low", v["difference"]["low"], "{:+.3f}", 100),
                       number(dk + ".difference.high", v["difference"]["high"], "{:+.3f}", 100),
                       number(dk + ".independent_runs_half_width", v["independent_runs_half_width"], "{:.3f}", 100));
    }
    o += "</tbody></table>\n";
    const double limit = 100 * designs[0]["criteria"][k]["limit"].get<double>();
    chart.x_range(0.5, static_cast<double>(designs.size()) + 0.5);
    std::vector<double> ticks;
    for (std::size_t d = 0; d < designs.size(); ++d) ticks.push_back(static_cast<double>(d + 1));
    chart.x_ticks(ticks);
    double top = limit;
    for (double h : hi) top = std::max(top, h);
    chart.y_range(0, top * 1.15 + 1e-9);
    chart.error_bars(x, lo, hi, palette(0));
    chart.points(x, y, palette(0), "mean share, 95 % interval", 4);
    chart.hline(limit, palette(5), fmt::format("limit {:g} %", limit));
    o += "<figure>" + chart.svg() + "</figure>\n";
  }
  return o;
}

}  // namespace j232::report
