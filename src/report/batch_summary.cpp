#include "report/batch_summary.hpp"

#include <fmt/format.h>

#include "assess/tally.hpp"
#include "report/comparison_report.hpp"
#include "report/html_page.hpp"
#include "report/html_table.hpp"
#include "report/svg_chart.hpp"
#include "report/text_safety.hpp"

namespace j232::report {

namespace {
using json = nlohmann::ordered_json;

std::string verdict_of(const BatchRow& r) {
  if (r.hazard) return (*r.hazard)["valid"].get<bool>() ? "field" : "field-invalid";
  return r.result ? (*r.result)["verdict"].get<std::string>() : "error";
}

// A field scenario's hazard distance in a direction, in words.
std::string distance_text(const json& d, bool conservative) {
  const bool beyond = d[conservative ? "conservative_beyond_range" : "beyond_range"].get<bool>();
  const double m = d[conservative ? "conservative_m" : "estimate_m"].get<double>();
  return beyond ? "beyond the range" : m <= 0 ? "none" : fmt::format("{:g} m", m);
}

// The P(pass) a result's verdict rests on (the replicates' share for a result written
// before the verdict had a basis).
json verdict_pass(const json& x) {
  if (!x.contains("verdict_basis")) return x["pass_probability"];
  const json& b = x["verdict_basis"];
  return {{"estimate", b["estimate"]}, {"low", b["low"]}, {"high", b["high"]}};
}
}  // namespace

json batch_summary_json(const std::vector<BatchRow>& rows, const json& comparison) {
  json list = json::array();
  std::size_t passed = 0, failed = 0, invalid = 0, errors = 0, fields = 0;
  for (const auto& r : rows) {
    json row = {{"scenario", r.scenario}, {"verdict", verdict_of(r)}};
    if (r.hazard) {
      const json& h = *r.hazard;
      ++fields;
      if (!h["valid"].get<bool>()) ++invalid, row["invalid_because"] = json::array({h["invalid_reason"]});
      row["title"] = h["title"];
      row["thrown_per_km"] = h["objects"]["thrown_per_km"];
      row["hazard_distance"] = h["hazard_distance"];
      json planes = json::array();
      for (const auto& p : h["planes"]) planes.push_back({{"name", p["name"]}, {"hazardous_per_km", p["hazardous_per_km"]}});
      row["planes"] = planes;
      row["report"] = relative_url(r.folder + "/hazard.html");
      row["result"] = relative_url(r.folder + "/hazard.json");
    } else if (r.result) {
      const json& x = *r.result;
      (x["verdict"] == "passes" ? passed : x["verdict"] == "invalid" ? invalid : failed) += 1;
      if (x["verdict"] == "invalid") row["invalid_because"] = x["invalid_because"];
      row["title"] = x["scenario"]["title"];
      row["verdict_settled"] = x["verdict_settled"];
      // The P(pass) each verdict rests on, named (the replicates' share for a result
      // written before the verdict had a basis).
      row["pass_probability"] = verdict_pass(x);
      row["pass_probability_basis"] = x.contains("verdict_basis") ? x["verdict_basis"]["name"] : json("replicates");
      row["required_pass_probability"] = x["required_pass_probability"];
      row["deciding_criterion"] = x["deciding_criterion"];
      json shares;
      for (std::size_t c = 0; c < 4; ++c) shares[assess::category_name(static_cast<int>(c))] = x["criteria"][c]["mean_share"];
      row["mean_shares"] = shares;
      row["replicates"] = x["replicates"];
      row["report"] = relative_url(r.folder + "/report.html");
      row["result"] = relative_url(r.folder + "/result.json");
      row["resumed"] = r.resumed;
    } else {
      ++errors;
      row["error"] = r.error;
    }
    list.push_back(row);
  }
  json summary = {{"program", "j232 batch"},
                  {"scenarios", rows.size()},
                  {"passed", passed},
                  {"failed", failed},
                  {"invalid", invalid},
                  {"refused", errors},
                  {"fields", fields},
                  {"all_passed", passed + fields == rows.size() && invalid == 0},
                  {"rows", list}};
  if (!comparison.is_null()) summary["comparison"] = comparison;
  return summary;
}

std::string batch_summary_csv(const std::vector<BatchRow>& rows) {
  std::string o =
      "scenario,title,verdict,settled,p_pass,p_pass_low,p_pass_high,p_pass_basis,required,hits_zone,punctures_zone,hits_outside,"
      "punctures_outside,deciding_criterion,replicates,report,error\n";
  for (const auto& r : rows) {
    if (r.hazard) {  // a field scenario: its title, its report; its figures in its hazard.csv
      o += fmt::format("{},{},{},,,,,,,,,,,,,{},{}\n", csv_text_cell(r.scenario), csv_text_cell((*r.hazard)["title"].get<std::string>()),
                       verdict_of(r), csv_text_cell(relative_url(r.folder + "/hazard.html")),
                       (*r.hazard)["valid"].get<bool>() ? "" : csv_text_cell("invalid: " + (*r.hazard)["invalid_reason"].get<std::string>()));
      continue;
    }
    if (!r.result) {
      o += fmt::format("{},,error,,,,,,,,,,,,,,{}\n", csv_text_cell(r.scenario), csv_text_cell(r.error));
      continue;
    }
    const json& x = *r.result;
    const json p = verdict_pass(x);
    o += fmt::format("{},{},{},{},{:.6g},{:.6g},{:.6g},{},{:g}", csv_text_cell(r.scenario),
                     csv_text_cell(x["scenario"]["title"].get<std::string>()), verdict_of(r), x["verdict_settled"].get<bool>(),
                     p["estimate"].get<double>(), p["low"].get<double>(), p["high"].get<double>(),
                     x.contains("verdict_basis") ? x["verdict_basis"]["name"].get<std::string>() : "replicates",
                     x["required_pass_probability"].get<double>());
    for (std::size_t c = 0; c < 4; ++c) o += fmt::format(",{:.6g}", x["criteria"][c]["mean_share"].get<double>());
    o += fmt::format(",{},{},{},{}\n", x["deciding_criterion"].get<std::string>(), x["replicates"].get<long long>(),
                     csv_text_cell(relative_url(r.folder + "/report.html")),
                     x["verdict"] == "invalid" ? csv_text_cell("invalid: " + x["invalid_because"][0].get<std::string>()) : "");
  }
  return o;
}

std::string batch_summary_html(const std::vector<BatchRow>& rows, const json& comparison) {
  const json summary = batch_summary_json(rows, comparison);
  std::string o = page_head("SAE J232 batch summary");
  o += "<header><h1>SAE J232 batch summary (simulated)</h1></header>\n";
  const bool all = summary["all_passed"].get<bool>();
  o += fmt::format(
      "<section class=\"verdict {}\"><p class=\"verdict-line\">{} of {} scenarios pass; {} fail; {} invalid (no "
      "verdict); {} refused as bad input.</p></section>\n",
      all ? "pass" : "fail", number("passed", summary["passed"], "{}"), number("scenarios", summary["scenarios"], "{}"),
      number("failed", summary["failed"], "{}"), number("invalid", summary["invalid"], "{}"), number("refused", summary["refused"], "{}"));
  HtmlTable tests("numbers", {"scenario", "verdict", "P(pass)<br><small>the verdict's basis</small>", "95 % interval", "required",
                              "hits, zone", "punctures, zone", "hits, outside", "punctures, outside", "replicates", "report"});
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    if (r.hazard) continue;  // in the field table below
    if (!r.result) {
      tests.row({escape(r.scenario), HtmlCell::of_class("verdict-cell", "refused"), HtmlCell::spanning(9, escape(r.error))},
                " class=\"error\"");
      continue;
    }
    const json& x = *r.result;
    const std::string k = fmt::format("rows.{}.", i);
    std::vector<HtmlCell> cells = {
        fmt::format("{}<br><small>{}</small>", escape(x["scenario"]["title"].get<std::string>()), escape(r.scenario)),
        HtmlCell::of_class("verdict-cell", verdict_of(r) + (verdict_of(r) != "invalid" && !x["verdict_settled"].get<bool>() ? " (not settled)" : "")),
        number(k + "pass_probability.estimate", verdict_pass(x)["estimate"], "{:.3f}"),
        fmt::format("{} – {}", number(k + "pass_probability.low", verdict_pass(x)["low"], "{:.3f}"),
                    number(k + "pass_probability.high", verdict_pass(x)["high"], "{:.3f}")),
        number(k + "required_pass_probability", x["required_pass_probability"], "{:.2f}")};
    for (std::size_t c = 0; c < 4; ++c)
      cells.emplace_back(number(k + "mean_shares." + assess::category_name(static_cast<int>(c)), x["criteria"][c]["mean_share"], "{:.2f}", 100) + " %");
    cells.emplace_back(number(k + "replicates", x["replicates"], "{}"));
    cells.emplace_back(fmt::format("<a href=\"{}\">report</a>", escape(relative_url(r.folder + "/report.html"))));
    tests.row(cells, fmt::format(" class=\"{}\"", verdict_of(r)));
  }
  o += tests.html() + "<p>Shares are the mean over replicates of each kind of mark as a share of the denominator the scenario "
       "sets; each report gives their spread and the criterion that decides its verdict.</p>\n";
  if (summary["fields"].get<std::size_t>() > 0) {
    HtmlTable fields("numbers", {"scenario", "thrown per km", "hazard distance: left, right, front, rear (estimate / conservative)",
                                 "planes: hazardous per km mowed (95 %)", "report"});
    for (const auto& r : rows) {
      if (!r.hazard) continue;
      const json& h = *r.hazard;
      std::string distances, planes;
      for (const auto& d : h["hazard_distance"])
        distances += fmt::format("{}{}: {} / {}", distances.empty() ? "" : "<br>", d["direction"].get<std::string>(), distance_text(d, false),
                                 distance_text(d, true));
      for (const auto& p : h["planes"])
        planes += fmt::format("{}{}: {:.3g} ({:.3g}-{:.3g})", planes.empty() ? "" : "<br>", escape(p["name"].get<std::string>()),
                              p["hazardous_per_km"]["value"].get<double>(), p["hazardous_per_km"]["low"].get<double>(),
                              p["hazardous_per_km"]["high"].get<double>());
      fields.row({fmt::format("{}<br><small>{}</small>{}", escape(h["title"].get<std::string>()), escape(r.scenario),
                              h["valid"].get<bool>() ? "" : "<br><strong>invalid:</strong> " + escape(h["invalid_reason"].get<std::string>())),
                  fmt::format("{:.0f}", h["objects"]["thrown_per_km"].get<double>()), distances, planes.empty() ? "-" : planes,
                  fmt::format("<a href=\"{}\">report</a>", escape(relative_url(r.folder + "/hazard.html")))},
                 fmt::format(" class=\"{}\"", verdict_of(r)));
    }
    o += "<h2>Field scenarios: thrown-object hazard (j232 hazard)</h2>\n" + fields.html();
  }
  if (!comparison.is_null())
    o += "<section id=\"comparison\">\n<h2>The designs compared (common random numbers; <a href=\"compare.html\">compare.html</a>)</h2>\n" +
         comparison_body_html(comparison, "comparison.") + "</section>\n";
  o += page_foot();
  return o;
}

}  // namespace j232::report
