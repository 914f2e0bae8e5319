#include "report/drivers_report.hpp"

#include <fmt/format.h>

#include "report/html_page.hpp"
#include "report/html_table.hpp"
#include "report/svg_chart.hpp"
#include "report/text_safety.hpp"

namespace j232::report {

using json = nlohmann::ordered_json;

json drivers_json(const study::Drivers& d, const std::string& criterion) {
  json ranked = json::array();
  for (const auto& driver : d.ranked) {
    json ends = json::array();
    for (const auto& e : driver.ends)
      ends.push_back({{"value", e.value},
                      {"verdict", e.verdict},
                      {"share", e.share},
                      {"change", {{"mean", e.change.mean}, {"low", e.change.low}, {"high", e.change.high}}},
                      {"p_pass_exact", e.p_pass_exact}});
    ranked.push_back({{"input", driver.input}, {"basis", driver.basis}, {"largest_change", driver.largest_change}, {"ends", ends}});
  }
  return {{"criterion", criterion},
          {"method",
           "each input of the uncertainty set at each end of its range (each value of a discrete input), every other input as "
           "the scenario has it, with the scenario's seed: common random numbers, each change against the scenario as written "
           "paired replicate by replicate (95 % interval, normal approximation); ranked by the largest change of the deciding "
           "criterion's mean share"},
          {"inputs_from", d.default_inputs ? "j232's default set of estimated inputs" : "the scenario's [uncertainty] inputs"},
          {"replicates", d.replicates},
          {"seed", d.seed},
          {"share_as_written", d.share},
          {"p_pass_exact_as_written", d.p_pass_exact},
          {"ranked", ranked}};
}

namespace {
std::string end_words(const json& e) {
  return fmt::format("{:+.2f} at {}", 100 * e.at("change").at("mean").get<double>(), e.at("value").get<std::string>());
}
}  // namespace

std::string drivers_text(const json& d) {
  std::string o = fmt::format("  What moves {} most (each input at its range's ends, {} paired replicates; change of its mean share, points):\n",
                              d.at("criterion").get<std::string>(), count_of(d.at("replicates"), "deciding_inputs.replicates"));
  if (d.at("ranked").empty() || d.at("ranked")[0].at("largest_change").get<double>() == 0.0)
    return o + fmt::format("    none of the {} inputs moves it at either end of its range, at these replicates\n", d.at("ranked").size());
  for (std::size_t i = 0; i < d.at("ranked").size() && i < kDriversShown; ++i) {
    const auto& r = d.at("ranked")[i];
    std::string ends;
    for (const auto& e : r.at("ends")) ends += (ends.empty() ? "" : ", ") + end_words(e);
    o += fmt::format("    {}. {}: {}\n", i + 1, terminal_safe(r.at("input").get<std::string>()), terminal_safe(ends));
  }
  return o;
}

std::string drivers_html(const json& r) {
  if (!r.contains("deciding_inputs")) return "";
  const json& d = r.at("deciding_inputs");
  std::string o = "<section id=\"drivers\">\n<h3>What moves the verdict</h3>\n";
  o += fmt::format(
      "<p>The deciding criterion, <strong>{}</strong>, with each uncertain input ({}) set to each end of its range and every other "
      "input as written: {} replicates each with the scenario's seed, so each change is paired replicate by replicate with the "
      "scenario as written (its share at these replicates: {} %; P(pass) from every nail {}).</p>\n",
      escape(d.at("criterion").get<std::string>()), escape(d.at("inputs_from").get<std::string>()), number("deciding_inputs.replicates", d.at("replicates"), "{}"),
      number("deciding_inputs.share_as_written", d.at("share_as_written"), "{:.2f}", 100),
      number("deciding_inputs.p_pass_exact_as_written", d.at("p_pass_exact_as_written"), "{:.3f}"));
  if (d.at("ranked").empty() || d.at("ranked")[0].at("largest_change").get<double>() == 0.0)
    return o + fmt::format("<p><strong>None of the {} inputs moves it</strong> at either end of its range, at these replicates: the verdict "
                           "does not rest on any one of them (result.json lists each end).</p>\n</section>\n",
                           d.at("ranked").size());
  HtmlTable table("numbers", {"input", "value", "share", "change, points (95 %, paired)", "P(pass) from every nail", "its own verdict",
                              "what the range rests on"});
  for (std::size_t i = 0; i < d.at("ranked").size() && i < kDriversShown; ++i) {
    const auto& in = d.at("ranked")[i];
    const std::string key = fmt::format("deciding_inputs.ranked.{}", i);
    for (std::size_t e = 0; e < in.at("ends").size(); ++e) {
      const auto& end = in.at("ends")[e];
      const std::string k = fmt::format("{}.ends.{}", key, e);
      // The input's name and its range's basis span its ends' rows.
      std::vector<HtmlCell> cells;
      if (e == 0) cells.push_back(HtmlCell::spanning_rows(in.at("ends").size(), escape(in.at("input").get<std::string>())));
      cells.insert(cells.end(),
                   {escape(end.at("value").get<std::string>()), number(k + ".share", end.at("share"), "{:.2f}", 100) + " %",
                    fmt::format("{} ({} to {})", number(k + ".change.mean", end.at("change").at("mean"), "{:+.2f}", 100),
                                number(k + ".change.low", end.at("change").at("low"), "{:+.2f}", 100),
                                number(k + ".change.high", end.at("change").at("high"), "{:+.2f}", 100)),
                    number(k + ".p_pass_exact", end.at("p_pass_exact"), "{:.3f}"), escape(end.at("verdict").get<std::string>())});
      if (e == 0) cells.push_back(HtmlCell::spanning_rows(in.at("ends").size(), escape(in.at("basis").get<std::string>())));
      table.row(cells);
    }
  }
  std::size_t runs = 1;  // the scenario as written, and each end
  for (const auto& in : d.at("ranked")) runs += in.at("ends").size();
  o += "<p>The three inputs that move it most:</p>\n" + table.html();
  o += fmt::format(
      "<p>Every input, ranked, is in result.json (<code>deciding_inputs</code>). One input at a time: what the "
      "inputs do together, and how much of the verdict's spread each carries, is <code>j232 uq</code>'s study (Sobol' indices). "
      "These {} runs were asked for with <code>--drivers</code>.</p>\n</section>\n",
      runs);
  return o;
}

}  // namespace j232::report
