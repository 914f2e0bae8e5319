#include "report/uncertainty_report.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <fmt/format.h>

#include "assess/statistics.hpp"
#include "flight/nail_flight.hpp"
#include "report/html_page.hpp"
#include "report/html_table.hpp"
#include "scenario/input_error.hpp"
#include "report/svg_chart.hpp"
#include "report/text_safety.hpp"

namespace j232::report {

namespace {
using json = nlohmann::ordered_json;
const char* scale_name(study::UqOutput::Scale s) {
  switch (s) {
    case study::UqOutput::Scale::Probability: return "probability";
    case study::UqOutput::Scale::Percent: return "share";
    case study::UqOutput::Scale::Number: return "number";
  }
  return "number";
}

json index_json(const study::Index& i) { return {{"estimate", i.estimate}, {"low", i.low}, {"high", i.high}}; }
}  // namespace

json uncertainty_json(const study::UncertaintyResult& r) {
  json inputs = json::array();
  for (const auto& in : r.plan.inputs) {
    if (!in.values.empty()) {
      // A discrete input: its values (uq.csv gives the index of the one drawn).
      std::string listed;
      for (const auto& v : in.values) listed += (listed.empty() ? "" : ", ") + v;
      inputs.push_back({{"parameter", in.parameter},
                        {"low", "one of: " + listed},
                        {"high", ""},
                        {"values", in.values},
                        {"distribution", fmt::format("discrete: each of its {} values equally likely (uq.csv: the index, from 0)", in.values.size())},
                        {"basis", in.basis}});
      continue;
    }
    inputs.push_back(
        {{"parameter", in.parameter},
         {"low", in.low},
         {"high", in.high},
         {"distribution", in.distribution == "triangular" ? fmt::format("triangular, mode {}", in.mode.empty() ? "midway" : in.mode)
                          : in.distribution == "normal"   ? fmt::format("normal about the midpoint, sd {}, truncated to the range",
                                                                      in.sd.empty() ? "a quarter of the range" : in.sd)
                          : in.distribution == "loguniform" ? "loguniform (uniform in the logarithm)"
                                                            : "uniform"},
         {"basis", in.basis}});
  }
  json outputs, sensitivity, listed = json::array();
  for (std::size_t o = 0; o < r.output_info.size(); ++o) {
    const study::UqOutput& info = r.output_info[o];
    listed.push_back({{"name", info.name}, {"words", info.words}, {"scale", scale_name(info.scale)}, {"unit", info.unit}});
    std::vector<double> v;
    for (const auto& out : r.outputs) v.push_back(out[o]);
    std::sort(v.begin(), v.end());
    double mean = 0;
    for (double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    outputs[info.name] = {{"mean", mean},
                                         {"min", v.front()},
                                         {"q05", assess::quantile_sorted(v, 0.05)},
                                         {"q50", assess::quantile_sorted(v, 0.5)},
                                         {"q95", assess::quantile_sorted(v, 0.95)},
                                         {"max", v.back()}};
    const auto& idx = r.indices[o];
    json rows = json::array();
    double moved = 0;  // the largest change of an index from N/2 to N base draws
    for (std::size_t i = 0; i < r.plan.inputs.size(); ++i) {
      json row = {{"input", r.plan.inputs[i].parameter},
                  {"first_order", index_json(idx.first[i])},
                  {"total", index_json(idx.total[i])},
                  {"flagged", study::leaves_unit_interval(idx.first[i]) || study::leaves_unit_interval(idx.total[i])}};
      if (r.half_indices) {
        const auto& half = (*r.half_indices)[o];
        row["at_half_the_draws"] = {{"first_order", half.first[i].estimate}, {"total", half.total[i].estimate}};
        if (half.variance > 0)
          moved = std::max({moved, std::abs(half.first[i].estimate - idx.first[i].estimate), std::abs(half.total[i].estimate - idx.total[i].estimate)});
      }
      rows.push_back(row);
    }
    sensitivity[info.name] = {{"variance", idx.variance},
                                             {"indices", rows},
                                             {"largest_change_from_half_the_draws", r.half_indices ? json(moved) : json(nullptr)}};
    // What Monte Carlo noise alone would give (none where not estimated), and its share of the variance.
    const double noise = o < r.noise_variance.size() ? r.noise_variance[o] : -1.0;
    sensitivity[info.name]["noise_variance"] = noise >= 0 ? json(noise) : json(nullptr);
    sensitivity[info.name]["noise_share"] = noise >= 0 && idx.variance > 0 ? json(noise / idx.variance) : json(nullptr);
  }
  // The verdict is the last output: 1 where the draw passes (a field: acceptable beyond the deck).
  const double passing = outputs[r.output_info.back().name]["mean"].get<double>();
  json j = {{"program", "j232 uq"},
            {"scenario", r.scenario_file},
            {"title", r.title},
            {"kind", r.field ? "field" : "j232"},
            {"method",
             std::string("Saltelli scheme on a Sobol' sequence (Boost.Random), N (k + 2) assessments with common random numbers (") +
                 (r.field ? "the same objects" : "the same seed and replicates") +
                 " at every draw); first-order indices by Saltelli et al. (2010), total by Jansen (1999); 95 % bootstrap intervals "
                 "(500 resamples of the base draws)"},
            {"inputs", inputs},
            {"default_inputs", r.plan.defaults},
            {"base_draws", r.plan.base_draws},
            {"base_draws_default", study::UncertaintyPlan{}.base_draws},
            {"assessments", r.outputs.size()}};
  if (r.field) {
    j["objects_per_assessment"] = r.plan.objects;
    j["acceptable_area_m2"] = r.acceptable_area;
    j["verdict_rule"] = "acceptable: the hazard distance is the deck's edge in every direction (hazardous impacts fewer than one per "
                        "acceptable area in every cell of the ground tallied beyond the deck)";
  } else {
    j["replicates_per_assessment"] = r.plan.replicates;
    j["required_pass_probability"] = r.required;
    j["verdict_rule"] = "passes: P(pass) from every nail at least the required";
  }
  j["seed"] = r.seed;
  j["share_of_draws_passing"] = passing;
  j["robust_verdict"] = passing == 1.0   ? (r.field ? "acceptable beyond the deck at every draw" : "passes at every draw")
                        : passing == 0.0 ? (r.field ? "hazardous beyond the deck at every draw" : "fails at every draw")
                                         : "depends on the inputs";
  j["ranked_by"] = r.output_info[r.smooth_output].name;
  j["output_list"] = listed;
  j["outputs"] = outputs;
  j["sensitivity"] = sensitivity;
  j["warnings"] = r.warnings;
  return j;
}

std::string uncertainty_csv(const study::UncertaintyResult& r) {
  std::string o = "assessment,block";
  for (const auto& in : r.plan.inputs) {
    o += ',';
    o += csv_text_cell(in.parameter);
  }
  for (const auto& out : r.output_info) o += "," + out.name;
  o += ",cut_off_share,cut_off_mostly_by\n";
  const std::size_t n = r.design.base;
  // Every number as the shortest text that reads back to the same double: the file holds
  // each assessment exactly, so a study can be rebuilt from it (`j232 uq --reuse`).
  for (std::size_t run = 0; run < r.outputs.size(); ++run) {
    const std::size_t block = run / n;
    const std::string b = block == 0 ? "A" : block == 1 ? "B" : fmt::format("AB{}", block - 1);
    o += fmt::format("{},{}", run + 1, b);
    for (double v : r.values[run]) o += fmt::format(",{}", v);
    for (double v : r.outputs[run]) o += fmt::format(",{}", v);
    const study::UqRun none;
    const study::UqRun& ran = run < r.runs.size() ? r.runs[run] : none;
    o += fmt::format(",{},{}\n", ran.cut_off_share, flight::cut_off_name(static_cast<flight::CutOff>(ran.cut_off_limit)));
  }
  return o;
}

UncertaintyTable read_uncertainty_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw scenario::InputError::file_problem(path, std::nullopt, "cannot be read (expected a finished study's uq.csv)");
  const auto split_line = [](const std::string& line) {
    std::vector<std::string> cells;
    std::size_t start = 0;
    for (;;) {
      const std::size_t comma = line.find(',', start);
      cells.push_back(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
      if (comma == std::string::npos) return cells;
      start = comma + 1;
    }
  };
  UncertaintyTable t;
  t.file = path;
  std::string line;
  if (!std::getline(in, line)) throw scenario::InputError::file_problem(path, 1, "is empty (expected a finished study's uq.csv)");
  const auto head = split_line(line);
  if (head.size() < 5 || head[0] != "assessment" || head[1] != "block" || head[head.size() - 2] != "cut_off_share" ||
      head.back() != "cut_off_mostly_by")
    throw scenario::InputError(path, 1, "header", line.substr(0, 80),
                               "expected a uq.csv of this version: assessment,block,<inputs>,<outputs>,cut_off_share,cut_off_mostly_by");
  t.columns.assign(head.begin() + 2, head.end() - 2);
  for (int number = 2; std::getline(in, line); ++number) {
    const auto cells = split_line(line);
    const auto refuse = [&](const std::string& column, const std::string& value, const std::string& expected) {
      throw scenario::InputError(path, number, column, value, expected);
    };
    if (cells.size() != head.size()) refuse("row", line.substr(0, 80), fmt::format("{} cells, as the header has", head.size()));
    if (cells[0] != std::to_string(t.cells.size() + 1)) refuse("assessment", cells[0], fmt::format("{}: the rows in order", t.cells.size() + 1));
    std::vector<double> row;
    for (std::size_t c = 2; c + 1 < cells.size(); ++c) {
      char* end = nullptr;
      const double v = std::strtod(cells[c].c_str(), &end);
      if (cells[c].empty() || *end != '\0') refuse(head[c], cells[c], "a number");
      row.push_back(v);
    }
    study::UqRun run;
    run.cut_off_share = row.back();
    row.pop_back();
    run.cut_off_limit = -1;
    for (int c = 0; c < flight::kCutOffReasons; ++c)
      if (cells.back() == flight::cut_off_name(static_cast<flight::CutOff>(c))) run.cut_off_limit = c;
    if (run.cut_off_limit < 0) refuse("cut_off_mostly_by", cells.back(), "the name of a run's limit (none, time_limit, max_bounces, ...)");
    t.cells.push_back(std::move(row));
    t.runs.push_back(run);
    t.lines.push_back(number);
  }
  return t;
}

namespace {

// The robust verdict: how many of the draws pass (a J232 test) or keep the ground beyond the
// deck acceptable (a field).
std::string robust_verdict_html(const json& j, bool field) {
  std::string o;
  const double passing = j.at("share_of_draws_passing").get<double>();
  const char* verdict_class = passing == 1.0 ? "pass" : passing == 0.0 ? "fail" : "invalid";
  if (field)
    o += fmt::format(
        "<p class=\"verdict {}\"><strong>Robust verdict: {}</strong> &mdash; hazardous impacts (a person's) stay below one per {} m&sup2; "
        "in every cell of the ground tallied beyond the deck in {} % of {} assessments drawn over the inputs' ranges.</p>\n",
        verdict_class, escape(j.at("robust_verdict").get<std::string>()), number("acceptable_area_m2", j.at("acceptable_area_m2"), "{:.4g}"),
        number("share_of_draws_passing", j.at("share_of_draws_passing"), "{:.1f}", 100), number("assessments", j.at("assessments"), "{}"));
  else
    o += fmt::format(
        "<p class=\"verdict {}\"><strong>Robust verdict: the mower {}</strong> &mdash; it passes (P(pass) at least {}) in "
        "{} % of {} assessments drawn over the inputs' ranges.</p>\n",
        verdict_class, escape(j.at("robust_verdict").get<std::string>()), number("required_pass_probability", j.at("required_pass_probability"), "{:g}"),
        number("share_of_draws_passing", j.at("share_of_draws_passing"), "{:.1f}", 100), number("assessments", j.at("assessments"), "{}"));
  return o;
}

// The study's warnings: how many, the first few, the rest folded.
std::string warnings_html(const json& j) {
  std::string o;
  if (j.contains("warnings") && !j.at("warnings").empty()) {
    const auto& w = j.at("warnings");
    constexpr std::size_t kShown = 3;
    o += fmt::format("<section class=\"warnings\"><p><strong>Before trusting every draw, note ({} warning{}):</strong></p>\n<ul class=\"warnings\">\n",
                     w.size(), w.size() == 1 ? "" : "s");
    for (std::size_t i = 0; i < w.size() && i < kShown; ++i) o += fmt::format("<li>{}</li>\n", escape(w[i].get<std::string>()));
    o += "</ul>\n";
    if (w.size() > kShown) {
      o += fmt::format("<details><summary>the other {}</summary>\n<ul class=\"warnings\">\n", w.size() - kShown);
      for (std::size_t i = kShown; i < w.size(); ++i) o += fmt::format("<li>{}</li>\n", escape(w[i].get<std::string>()));
      o += "</ul></details>\n";
    }
    o += "</section>\n";
  }
  return o;
}

// The design (assessments, draws, seed) and the table of inputs with their ranges and bases.
std::string inputs_html(const json& j, bool field) {
  std::string o;
  o += fmt::format(
      "<p>{} assessments of {} each (Saltelli scheme, {} base draws{}; common random numbers, seed {}). "
      "Inputs{}:</p>\n",
      number("assessments", j.at("assessments"), "{}"),
      field ? number("objects_per_assessment", j.at("objects_per_assessment"), "{}") + " objects"
            : number("replicates_per_assessment", j.at("replicates_per_assessment"), "{}") + " replicates",
      number("base_draws", j.at("base_draws"), "{}"),
      j.at("base_draws").get<std::size_t>() < j.at("base_draws_default").get<std::size_t>()
          ? fmt::format(", fewer than the default {}, as the scenario asks", j.at("base_draws_default").get<std::size_t>())
          : "",
      number("seed", j.at("seed"), "{}"),
      j.at("default_inputs").get<bool>() ? (field ? " (j232's default set of a field's estimated inputs: the scenario has no [uncertainty])"
                                                : " (j232's default set of estimated inputs: the scenario has no [uncertainty])")
                                      : "");
  const auto& inputs = j.at("inputs");
  HtmlTable table("", {"#", "input", "from", "to", "distribution", "basis of the range"});
  for (std::size_t i = 0; i < inputs.size(); ++i)
    table.row({std::to_string(i + 1), escape(inputs[i].at("parameter").get<std::string>()), escape(inputs[i].at("low").get<std::string>()),
               escape(inputs[i].at("high").get<std::string>()), escape(inputs[i].at("distribution").get<std::string>()),
               escape(inputs[i].at("basis").get<std::string>())});
  return o + table.html();
}

// Each output's mean, quantiles and range over the draws.
std::string outputs_html(const json& j, bool field) {
  HtmlTable table("numbers", {"output", "mean", "5 %", "median", "95 %", "min", "max"});
  const auto& listed = j.at("output_list");
  for (std::size_t k = 0; k + 1 < listed.size(); ++k) {  // the verdict's share of draws is above
    const std::string name = listed[k].at("name"), scale_of = listed[k].at("scale");
    const auto& x = j.at("outputs")[name];
    const double scale = scale_of == "share" ? 100.0 : 1.0;
    // A field's probabilities of being struck are small: shown to three significant digits.
    const char* f = scale_of == "probability" ? (field ? "{:.3g}" : "{:.3f}") : scale_of == "share" ? "{:.2f}" : "{:.4g}";
    const std::string unit = scale_of == "share" ? " %" : listed[k].at("unit").get<std::string>();
    std::vector<HtmlCell> cells = {escape(listed[k].at("words").get<std::string>())};
    for (const char* q : {"mean", "q05", "q50", "q95", "min", "max"})
      cells.emplace_back(number(fmt::format("outputs.{}.{}", name, q), x[q], f, scale) + escape(unit));
    table.row(cells);
  }
  return "<h2>The outputs over the inputs' uncertainty</h2>\n" + table.html();
}

// One output's Sobol' indices: the table, what the noise and the intervals allow, the
// convergence from half the draws, and the chart.
std::string sobol_html(const json& j, const json& output) {
  std::string o;
  const std::string name = output.at("name"), words = escape(output.at("words").get<std::string>());
  const auto& s = j.at("sensitivity")[name];
  if (s.at("variance").get<double>() <= 0) {
    // The variance is over the base draws (A and B); the table's range is over every draw.
    const auto& x = j.at("outputs")[name];
    if (x.at("min").get<double>() == x.at("max").get<double>())
      o += fmt::format("<p>{}: the same at every draw (no variance to attribute).</p>\n", words);
    else
      o += fmt::format(
          "<p>{}: the same at every base draw (A and B), so there is no variance to attribute, though it moves at "
          "some of the mixed draws (from {} to {} over all of them): more base draws are needed to apportion it.</p>\n",
          words, x.at("min").get<double>(), x.at("max").get<double>());
    return o;
  }
  Chart chart(fmt::format("Sobol' indices: {}", output.at("words").get<std::string>()), "input (numbered as in the table above)", "index", 640, 300);
  std::vector<double> x1, y1, l1, h1, x2, y2, l2, h2;
  const bool half = !s.at("largest_change_from_half_the_draws").is_null();
  bool any_flagged = false;
  for (const auto& row : s.at("indices")) any_flagged = any_flagged || row.at("flagged").get<bool>();
  std::vector<HtmlCell> header = {words, "first order", "95 %", "total", "95 %"};
  if (half) header.emplace_back(fmt::format("first / total at N = {}", j.at("base_draws").get<std::size_t>() / 2));
  header.emplace_back("");
  HtmlTable table("numbers", header);
  for (std::size_t i = 0; i < s.at("indices").size(); ++i) {
    const auto& row = s.at("indices")[i];
    const std::string key = fmt::format("sensitivity.{}.indices.{}", name, i);
    x1.push_back(static_cast<double>(i + 1) - 0.12), y1.push_back(row.at("first_order").at("estimate")),
        l1.push_back(row.at("first_order").at("low")), h1.push_back(row.at("first_order").at("high"));
    x2.push_back(static_cast<double>(i + 1) + 0.12), y2.push_back(row.at("total").at("estimate")), l2.push_back(row.at("total").at("low")),
        h2.push_back(row.at("total").at("high"));
    std::vector<HtmlCell> cells = {
        fmt::format("{} {}", i + 1, escape(row.at("input").get<std::string>())),
        number(key + ".first_order.estimate", row.at("first_order").at("estimate"), "{:.3f}"),
        fmt::format("{} to {}", number(key + ".first_order.low", row.at("first_order").at("low"), "{:.3f}"),
                    number(key + ".first_order.high", row.at("first_order").at("high"), "{:.3f}")),
        number(key + ".total.estimate", row.at("total").at("estimate"), "{:.3f}"),
        fmt::format("{} to {}", number(key + ".total.low", row.at("total").at("low"), "{:.3f}"), number(key + ".total.high", row.at("total").at("high"), "{:.3f}"))};
    if (half)
      cells.emplace_back(fmt::format("{} / {}", number(key + ".at_half_the_draws.first_order", row.at("at_half_the_draws").at("first_order"), "{:.3f}"),
                                     number(key + ".at_half_the_draws.total", row.at("at_half_the_draws").at("total"), "{:.3f}")));
    cells.emplace_back(row.at("flagged").get<bool>() ? "&#9873; interval leaves [0, 1] by more than 0.05" : "");
    table.row(cells);
  }
  o += table.html();
  if (!s.at("noise_share").is_null() && s.at("noise_share").get<double>() >= 0.25)
    o += fmt::format(
        "<p class=\"warning\">Mostly chance: Monte Carlo noise alone would give {} % of this output's variance over the draws "
        "(binomial, as if each draw met new nails; common random numbers make it less). Its marks are rare, and a change of any "
        "input sends the few nails that make them elsewhere: a total index near or above 1 here says that, not that the input "
        "decides it. Read the inputs' effect on it from P(pass) from every nail, or run more replicates per draw.</p>\n",
        number(fmt::format("sensitivity.{}.noise_share", name), s.at("noise_share"), "{:.0f}", 100));
  if (any_flagged)
    o += fmt::format(
        "<p>&#9873; An index lies between 0 and 1; an interval that leaves [0, 1] by more than 0.05 says that at N = {} base draws the estimate is "
        "as much the estimator's noise as the input's effect: read it as no more precise than its interval, or run more base "
        "draws ([uncertainty] base_draws).</p>\n",
        j.at("base_draws").get<std::size_t>());
  if (half)
    o += fmt::format("<p>Convergence: from N = {} to N = {} base draws the indices moved by at most {}{}.</p>\n",
                     j.at("base_draws").get<std::size_t>() / 2, number("base_draws", j.at("base_draws"), "{}"),
                     number(fmt::format("sensitivity.{}.largest_change_from_half_the_draws", name), s.at("largest_change_from_half_the_draws"), "{:.3f}"),
                     s.at("largest_change_from_half_the_draws").get<double>() > 0.05 ? " (more than 0.05: more base draws would still move them)"
                                                                                 : "");
  std::vector<double> ticks;
  for (std::size_t i = 0; i < s.at("indices").size(); ++i) ticks.push_back(static_cast<double>(i + 1));
  chart.x_range(0.5, static_cast<double>(ticks.size()) + 0.5);
  chart.x_ticks(ticks);
  double lo = 0, hi = 1;
  for (double v : l1) lo = std::min(lo, v);
  for (double v : h2) hi = std::max(hi, v);
  chart.y_range(lo, hi);
  chart.error_bars(x1, l1, h1, palette(0));
  chart.points(x1, y1, palette(0), "first order", 4);
  chart.error_bars(x2, l2, h2, palette(1));
  chart.points(x2, y2, palette(1), "total", 4);
  o += "<figure>" + chart.svg() + "</figure>\n";
  return o;
}

}  // namespace

std::string uncertainty_html(const json& j) {
  std::string o = page_head("j232 uncertainty study: " + j.at("title").get<std::string>());
  o += fmt::format("<h1>How much the verdict rests on uncertain inputs</h1>\n<p>{} ({})</p>\n", escape(j.at("title").get<std::string>()),
                   escape(j.at("scenario").get<std::string>()));
  const bool field = j.at("kind") == "field";
  o += robust_verdict_html(j, field);
  o += warnings_html(j);  // after the verdict, before the inputs
  o += inputs_html(j, field);
  o += outputs_html(j, field);
  o += "<h2>Which input drives what: Sobol' indices</h2>\n<p>First order: the share of the output's variance "
       "an input causes alone; total: alone and with all its interactions. An input with both near 0 does not matter over its "
       "range. Bars: 95 % bootstrap intervals.</p>\n";
  for (const auto& output : j.at("output_list")) o += sobol_html(j, output);
  o += page_foot();
  return o;
}

}  // namespace j232::report

namespace j232::report {

json uncertainty_summary_json(const json& study) {
  json s;
  s["files"] = "uq.html, uq.json, uq.csv";
  s["inputs"] = study["inputs"].size();
  s["default_inputs"] = study["default_inputs"];
  s["assessments"] = study["assessments"];
  s["replicates_per_assessment"] = study["replicates_per_assessment"];
  s["robust_verdict"] = study["robust_verdict"];
  s["share_of_draws_passing"] = study["share_of_draws_passing"];
  s["p_pass"] = study["outputs"]["p_pass"];
  s["p_pass_exact"] = study["outputs"]["p_pass_exact"];
  // The inputs by their total index for P(pass) from every nail (smooth in the inputs, where
  // the share of passing replicates moves in steps), largest first (none when it does not vary).
  std::vector<json> drivers;
  for (const auto& row : study["sensitivity"]["p_pass_exact"]["indices"])
    drivers.push_back({{"input", row["input"]}, {"total", row["total"]}});
  std::stable_sort(drivers.begin(), drivers.end(), [](const json& a, const json& b) {
    return a["total"]["estimate"].get<double>() > b["total"]["estimate"].get<double>();
  });
  s["p_pass_variance"] = study["sensitivity"]["p_pass_exact"]["variance"];
  s["drivers_of_p_pass"] = drivers;
  return s;
}

std::string uncertainty_summary_text(const json& s) {
  std::string o = fmt::format("  Uncertainty study ({} inputs, {} assessments): {}; {:.1f} % of the inputs' draws pass\n",
                              s.at("inputs").get<std::size_t>(), s.at("assessments").get<std::size_t>(), s.at("robust_verdict").get<std::string>(),
                              100 * s.at("share_of_draws_passing").get<double>());
  if (s.at("p_pass_variance").get<double>() > 0 && !s.at("drivers_of_p_pass").empty()) {
    const auto& top = s.at("drivers_of_p_pass")[0];
    o += fmt::format("  What drives the verdict most: {} (total Sobol' index {:.2f})\n", terminal_safe(top.at("input").get<std::string>()),
                     top.at("total").at("estimate").get<double>());
  }
  return o;
}

std::string uncertainty_summary_html(const json& r) {
  const json& s = r.at("uncertainty");
  std::string o = "<section id=\"uncertainty\">\n<h2>How much the verdict rests on estimated inputs</h2>\n";
  o += fmt::format(
      "<p>The uncertain inputs ({}{}) were drawn together, {} assessments of {} replicates each with common random numbers "
      "(<a href=\"uq.html\">the study</a>). <strong>Robust verdict: {}</strong>: the mower passes in {} % of the draws; "
      "P(pass) over the inputs has median {} and 5–95 % range {} to {}.</p>\n",
      number("uncertainty.inputs", s.at("inputs"), "{}"),
      s.at("default_inputs").get<bool>() ? ", j232's default set of estimated inputs" : ", the scenario's [uncertainty]",
      number("uncertainty.assessments", s.at("assessments"), "{}"),
      number("uncertainty.replicates_per_assessment", s.at("replicates_per_assessment"), "{}"), escape(s.at("robust_verdict").get<std::string>()),
      number("uncertainty.share_of_draws_passing", s.at("share_of_draws_passing"), "{:.1f}", 100),
      number("uncertainty.p_pass.q50", s.at("p_pass").at("q50"), "{:.3f}"), number("uncertainty.p_pass.q05", s.at("p_pass").at("q05"), "{:.3f}"),
      number("uncertainty.p_pass.q95", s.at("p_pass").at("q95"), "{:.3f}"));
  if (s.at("p_pass_variance").get<double>() > 0) {
    HtmlTable table("numbers", {"input", "total Sobol' index for P(pass) from every nail", "95 % interval"});
    for (std::size_t i = 0; i < s.at("drivers_of_p_pass").size(); ++i) {
      const auto& d = s.at("drivers_of_p_pass")[i];
      const std::string key = fmt::format("uncertainty.drivers_of_p_pass.{}.total", i);
      table.row({escape(d.at("input").get<std::string>()), number(key + ".estimate", d.at("total").at("estimate"), "{:.3f}"),
                 fmt::format("{} to {}", number(key + ".low", d.at("total").at("low"), "{:.3f}"), number(key + ".high", d.at("total").at("high"), "{:.3f}"))});
    }
    o += table.html();
  } else {
    o += s.at("p_pass_exact").at("min").get<double>() == s.at("p_pass_exact").at("max").get<double>()
             ? "<p>P(pass) is the same at every draw: no input moves the verdict over its range.</p>\n"
             : "<p>P(pass) from every nail is the same at every base draw: the study's draws are too few to say which input "
               "moves it.</p>\n";
  }
  return o + "</section>\n";
}

}  // namespace j232::report
