#include "report/comparison_report.hpp"

#include <fmt/format.h>

#include "assess/tally.hpp"
#include "report/html_page.hpp"
#include "report/html_table.hpp"
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
    const auto k = static_cast<std::size_t>(d.deciding);
    designs.push_back({{"scenario", d.file},
                       {"title", d.title},
                       {"verdict", d.verdict},
                       {"verdict_settled", d.settled},
                       {"verdict_basis", d.basis},
                       {"invalid_because", d.invalid_because},
                       {"required_pass_probability", d.required},
                       {"pass_probability", {{"estimate", d.pass.estimate}, {"low", d.pass.low}, {"high", d.pass.high}}},
                       {"pass_probability_exact",
                        d.exact.computed ? json{{"computed", true}, {"estimate", d.exact.value}, {"low", d.exact.low}, {"high", d.exact.high}}
                                         : json{{"computed", false}, {"why_not", d.exact.not_computed}}},
                       {"deciding_criterion",
                        {{"name", assess::category_name(d.deciding)},
                         {"limit", d.limits[k]},
                         {"mean_share", d.shares[k].mean},
                         {"margin", d.limits[k] - d.shares[k].mean},
                         {"pass_probability", d.deciding_pass}}},
                       {"criteria", criteria},
                       {"marks", d.marks},
                       {"nails", d.nails},
                       {"exit_speed_over_tip_speed", {{"mean", d.exit_speed_over_tip.mean}, {"standard_error", d.exit_speed_over_tip.standard_error}}},
                       {"strikes_per_struck_nail",
                        {{"mean", d.strikes_per_struck_nail.mean}, {"standard_error", d.strikes_per_struck_nail.standard_error}}}});
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
                     {"replicates_differing", v.replicates_differing},
                     {"differing_at_most", v.differing_at_most},
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

// One row per design and measure: first each design's P(pass) (its verdict, both
// estimates), then each criterion's share (marking the one that decides the design's
// verdict, with its margin to the limit), each with the design's difference from design 1.
std::string comparison_csv(const study::Comparison& c) {
  std::string out =
      "measure,design,scenario,verdict,limit,value,low,high,decides,margin,minus_design_1,difference_low,difference_high,"
      "independent_runs_half_width\n";
  const auto differences = [&](std::size_t d, const study::MeanInterval& m, double independent) {
    return d == 0 ? std::string(",,,") : fmt::format("{:.6g},{:.6g},{:.6g},{:.6g}", m.mean, m.low, m.high, independent);
  };
  for (std::size_t d = 0; d < c.designs.size(); ++d) {
    const auto& x = c.designs[d];
    const study::MeanInterval none;
    out += fmt::format("p_pass,{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},,,{}\n", d + 1, csv_text_cell(x.file), x.verdict, x.required,
                       x.pass.estimate, x.pass.low, x.pass.high,
                       d == 0 ? differences(0, none, 0) : differences(d, c.versus_first[d - 1].pass, c.versus_first[d - 1].independent_pass_half_width));
    if (x.exact.computed)
      out += fmt::format("p_pass_exact,{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},,,,,,\n", d + 1, csv_text_cell(x.file), x.verdict, x.required,
                         x.exact.value, x.exact.low, x.exact.high);
  }
  for (int k = 0; k < 4; ++k)
    for (std::size_t d = 0; d < c.designs.size(); ++d) {
      const auto& x = c.designs[d];
      const auto kk = static_cast<std::size_t>(k);
      const auto& s = x.shares[kk];
      const bool decides = x.deciding == k;
      out += fmt::format("{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{},{},", assess::category_name(k), d + 1, csv_text_cell(x.file), x.verdict,
                         x.limits[kk], s.mean, s.low, s.high, decides ? 1 : 0, decides ? fmt::format("{:.6g}", x.limits[kk] - s.mean) : "");
      out += d == 0 ? differences(0, {}, 0) : differences(d, c.versus_first[d - 1].shares[kk], c.versus_first[d - 1].independent_half_width[kk]);
      out += "\n";
    }
  return out;
}

std::string comparison_text(const study::Comparison& c) {
  std::string out;
  for (std::size_t d = 0; d < c.designs.size(); ++d) {
    const auto& x = c.designs[d];
    std::string verdict = x.verdict == "invalid" ? "NO VERDICT (invalid)" : x.verdict == "passes" ? "PASSES" : "FAILS";
    if (x.verdict != "invalid" && !x.settled) verdict += ", not settled";
    out += fmt::format("design {}: {}  {}\n", d + 1, verdict, terminal_safe(x.title));
    if (x.verdict == "invalid") {
      for (const auto& why : x.invalid_because) out += fmt::format("  - {}\n", terminal_safe(why));
      continue;
    }
    out += fmt::format("  P(pass one test) {:.3f} ({:.3f} to {:.3f})", x.pass.estimate, x.pass.low, x.pass.high);
    if (x.exact.computed) out += fmt::format("; from every nail {:.3f} ({:.3f} to {:.3f})", x.exact.value, x.exact.low, x.exact.high);
    out += fmt::format("; required {:.2f}; the verdict on {}\n", x.required, x.basis == "every_nail" ? "every nail" : "the replicates");
    const auto k = static_cast<std::size_t>(x.deciding);
    out += fmt::format("  decided by {}: mean {:.2f} % against its {:.1f} % limit (margin {:+.2f} points; the criterion passes in {:.1f} % of tests)\n",
                       assess::category_name(x.deciding), 100 * x.shares[k].mean, 100 * x.limits[k], 100 * (x.limits[k] - x.shares[k].mean),
                       100 * x.deciding_pass);
  }
  static const char* names[] = {"hits in the zone", "punctures in the zone", "hits outside", "punctures outside"};
  for (std::size_t d = 1; d < c.designs.size(); ++d) {
    const auto& v = c.versus_first[d - 1];
    out += fmt::format("design {} minus design 1 (95 % interval; independent runs would give +/-):\n", d + 1);
    if (v.replicates_differing == 0)
      out += fmt::format(
          "  no replicate differs: every share and verdict the same in all {} (the share of replicates that could differ is at "
          "most {:.2g}, 95 %)\n",
          c.replicates, v.differing_at_most);
    else
      out += fmt::format("  {} of {} replicates differ in a share or the verdict\n", v.replicates_differing, c.replicates);
    out += fmt::format("  P(pass)                {:+.3f} ({:+.3f} to {:+.3f}; +/-{:.3f})\n", v.pass.mean, v.pass.low, v.pass.high,
                       v.independent_pass_half_width);
    for (int k = 0; k < assess::kCategories; ++k) {
      const auto& m = v.shares[static_cast<std::size_t>(k)];
      out += fmt::format("  {:<23}{:+.3f} % ({:+.3f} to {:+.3f} %; +/-{:.3f} %)\n", names[k], 100 * m.mean, 100 * m.low, 100 * m.high,
                         100 * v.independent_half_width[static_cast<std::size_t>(k)]);
    }
  }
  return out;
}

std::string comparison_html(const json& c) {
  return page_head("j232 comparison of designs") + "<h1>Comparison of designs</h1>\n" + comparison_body_html(c, "") + page_foot();
}

std::string comparison_body_html(const json& c, const std::string& prefix) {
  const auto& designs = c.at("designs");
  auto number = [&](const std::string& key, const json& value, const char* format, double scale = 1.0) {
    return report::number(prefix + key, value, format, scale);
  };
  std::string o = "<ol>\n";
  for (const auto& d : designs)
    o += fmt::format("<li>{} ({})</li>\n", escape(d.at("title").get<std::string>()), escape(d.at("scenario").get<std::string>()));
  o += fmt::format(
      "</ol>\n<p>{} replicates of the whole test each, seed {}, with common random numbers: replicate r of "
      "every design drops its nails from the same random feed, so the differences below are judged replicate "
      "by replicate and their intervals are far tighter than those of independent runs (shown for "
      "comparison).</p>\n",
      number("replicates", c.at("replicates"), "{}"), number("seed", c.at("seed"), "{}"));
  // Each design's own verdict first, as its run would give it.
  o += "<h2>Each design's verdict</h2>\n";
  HtmlTable verdicts("numbers", {"design", "verdict", "P(pass one test)", "from every nail", "decided by", "mean share", "limit", "margin"});
  for (std::size_t d = 0; d < designs.size(); ++d) {
    const auto& x = designs[d];
    const std::string key = fmt::format("designs.{}.", d);
    if (!x.contains("verdict")) continue;
    const std::string verdict = x.at("verdict").get<std::string>();
    if (verdict == "invalid") {
      std::string why;
      for (const auto& w : x.at("invalid_because")) why += (why.empty() ? "" : "; ") + w.get<std::string>();
      verdicts.row({fmt::format("{}", d + 1), "no verdict (invalid)", HtmlCell::spanning(6, escape(why))});
      continue;
    }
    const auto& p = x.at("pass_probability");
    const auto& e = x.at("pass_probability_exact");
    const auto& dc = x.at("deciding_criterion");
    verdicts.row({fmt::format("{}", d + 1), number(key + "verdict", x.at("verdict"), "{}") + (x.at("verdict_settled").get<bool>() ? "" : " (not settled)"),
                  fmt::format("{} ({} to {})", number(key + "pass_probability.estimate", p.at("estimate"), "{:.3f}"),
                              number(key + "pass_probability.low", p.at("low"), "{:.3f}"), number(key + "pass_probability.high", p.at("high"), "{:.3f}")),
                  e.value("computed", false)
                      ? fmt::format("{} ({} to {})", number(key + "pass_probability_exact.estimate", e.at("estimate"), "{:.3f}"),
                                    number(key + "pass_probability_exact.low", e.at("low"), "{:.3f}"),
                                    number(key + "pass_probability_exact.high", e.at("high"), "{:.3f}"))
                      : std::string("&mdash;"),
                  escape(dc.at("name").get<std::string>()), number(key + "deciding_criterion.mean_share", dc.at("mean_share"), "{:.2f}", 100) + " %",
                  number(key + "deciding_criterion.limit", dc.at("limit"), "{:.1f}", 100) + " %",
                  number(key + "deciding_criterion.margin", dc.at("margin"), "{:+.2f}", 100) + " points"});
  }
  o += verdicts.html();
  // P(pass)
  o += "<h2>P(pass one test)</h2>\n";
  const std::vector<HtmlCell> versus = {"minus design 1", "95 % interval", "independent runs: &plusmn;"};
  const auto header = [&](std::vector<HtmlCell> own) {
    own.insert(own.end(), versus.begin(), versus.end());
    return own;
  };
  HtmlTable pass("numbers", header({"design", "P(pass)", "95 % interval"}));
  for (std::size_t d = 0; d < designs.size(); ++d) {
    const std::string key = fmt::format("designs.{}.pass_probability", d);
    const auto& p = designs[d].at("pass_probability");
    std::vector<HtmlCell> cells = {fmt::format("{}", d + 1), number(key + ".estimate", p.at("estimate"), "{:.3f}"),
                                   fmt::format("{} to {}", number(key + ".low", p.at("low"), "{:.3f}"), number(key + ".high", p.at("high"), "{:.3f}"))};
    if (d == 0) {
      cells.insert(cells.end(), {"&mdash;", "", ""});
    } else {
      const std::string dk = fmt::format("differences.{}", d - 1);
      const auto& v = c.at("differences")[d - 1];
      cells.insert(cells.end(), {number(dk + ".pass_probability.mean", v.at("pass_probability").at("mean"), "{:+.3f}"),
                                 fmt::format("{} to {}", number(dk + ".pass_probability.low", v.at("pass_probability").at("low"), "{:+.3f}"),
                                             number(dk + ".pass_probability.high", v.at("pass_probability").at("high"), "{:+.3f}")),
                                 number(dk + ".independent_runs_pass_half_width", v.at("independent_runs_pass_half_width"), "{:.3f}")});
    }
    pass.row(cells);
  }
  o += pass.html();
  // How many replicates differ at all: a zero-wide interval below means none did.
  for (std::size_t d = 1; d < designs.size(); ++d) {
    const auto& v = c.at("differences")[d - 1];
    if (!v.contains("replicates_differing")) continue;
    const std::string dk = fmt::format("differences.{}", d - 1);
    o += v.at("replicates_differing").get<std::uint64_t>() == 0
             ? fmt::format("<p>Design {}: no replicate differs from design 1 in any share or its verdict, so its shares' paired "
                           "intervals are zero-wide; the share of replicates that could differ is at most {} (95 %). (P(pass)'s "
                           "difference has Newcombe's paired interval, which says how large a difference the run could have missed.)</p>\n",
                           d + 1, number(dk + ".differing_at_most", v.at("differing_at_most"), "{:.2g}"))
             : fmt::format("<p>Design {}: {} of {} replicates differ from design 1 in a share or the verdict.</p>\n", d + 1,
                           number(dk + ".replicates_differing", v.at("replicates_differing"), "{}"), c.at("replicates").get<std::uint64_t>());
  }
  // Each criterion: a table row per design and a chart with the limit.
  for (int k = 0; k < 4; ++k) {
    o += fmt::format("<h2>{}</h2>\n", kCriterionWords[k]);
    HtmlTable shares("numbers", header({"design", "mean share", "95 % interval"}));
    Chart chart(fmt::format("{}: each design's mean share and its 95 % interval", kCriterionWords[k]), "design",
                "mean share of the nails fed (%)", 640, 300);
    std::vector<double> x, y, lo, hi;
    for (std::size_t d = 0; d < designs.size(); ++d) {
      const std::string key = fmt::format("designs.{}.criteria.{}.share", d, k);
      const auto& s = designs[d].at("criteria")[k].at("share");
      x.push_back(static_cast<double>(d + 1));
      y.push_back(100 * s.at("mean").get<double>());
      lo.push_back(100 * s.at("low").get<double>());
      hi.push_back(100 * s.at("high").get<double>());
      std::vector<HtmlCell> cells = {fmt::format("{}", d + 1), number(key + ".mean", s.at("mean"), "{:.3f}", 100) + " %",
                                     fmt::format("{} to {} %", number(key + ".low", s.at("low"), "{:.3f}", 100), number(key + ".high", s.at("high"), "{:.3f}", 100))};
      if (d == 0) {
        cells.insert(cells.end(), {"&mdash;", "", ""});
      } else {
        const std::string dk = fmt::format("differences.{}.criteria.{}", d - 1, k);
        const auto& v = c.at("differences")[d - 1].at("criteria")[k];
        cells.insert(cells.end(), {number(dk + ".difference.mean", v.at("difference").at("mean"), "{:+.3f}", 100) + " %",
                                   fmt::format("{} to {} %", number(dk + ".difference.low", v.at("difference").at("low"), "{:+.3f}", 100),
                                               number(dk + ".difference.high", v.at("difference").at("high"), "{:+.3f}", 100)),
                                   number(dk + ".independent_runs_half_width", v.at("independent_runs_half_width"), "{:.3f}", 100) + " %"});
      }
      shares.row(cells);
    }
    o += shares.html();
    const double limit = 100 * designs[0].at("criteria")[k].at("limit").get<double>();
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
