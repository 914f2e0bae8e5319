#include "report/compliance_report.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include <stdexcept>

#include "assess/statistics.hpp"
#include "report/board_views.hpp"
#include "report/html_page.hpp"
#include "report/html_table.hpp"
#include "report/drivers_report.hpp"
#include "report/uncertainty_report.hpp"
#include "report/svg_chart.hpp"

namespace j232::report {

namespace {

using json = nlohmann::ordered_json;

// A histogram as bars of "% of nails per bin", cut at the 99.9 % quantile so a few
// outliers do not squash the picture (the cut is stated in the caption).
Chart histogram_chart(const json& saved, const std::string& title, const std::string& x_title, const char* unit,
                      const std::string& of_what, const std::string& colour) {
  // The histogram as the run had it (its mean from the saved one: the sum is not saved).
  assess::Histogram h(saved.at("bin_width").get<double>(), 0, saved.at("first_bin_from").get<double>());
  for (const auto& c : saved.at("counts")) h.counts.push_back(count_of(c, "a histogram's counts"));
  if (h.counts.empty()) throw std::out_of_range("a histogram's counts: expected at least one bin");
  if (!(h.bin_width > 0)) throw std::out_of_range(fmt::format("a histogram's bin_width: expected above 0, not {}", h.bin_width));
  h.total = count_of(saved.at("count"), "a histogram's count");
  h.sum = saved.at("mean").get<double>() * static_cast<double>(h.total);
  Chart chart(title, x_title, fmt::format("share of {} per {:g} {} bin (%)", of_what, h.bin_width, unit));
  // From the first bin (or, for a histogram below zero, the lowest recorded value's) to the
  // 99.9th percentile.
  const double cut = std::max(h.quantile(0.999) + 2 * h.bin_width, h.origin + 5 * h.bin_width);
  std::size_t first = 0;
  if (h.origin < 0)
    while (first + 1 < h.counts.size() && h.counts[first] == 0 && h.origin + static_cast<double>(first + 1) * h.bin_width < 0) ++first;
  if (first > 0) first = first > 2 ? first - 2 : 0;
  std::vector<double> edges{h.origin + static_cast<double>(first) * h.bin_width}, heights;
  for (std::size_t i = first; i < h.counts.size() && edges.back() < cut; ++i) {
    heights.push_back(h.total ? 100.0 * static_cast<double>(h.counts[i]) / static_cast<double>(h.total) : 0.0);
    edges.push_back(h.origin + static_cast<double>(i + 1) * h.bin_width);
  }
  chart.bars(edges, heights, colour, "");
  chart.x_range(edges.front(), edges.back());
  chart.caption(
      fmt::format("{} values; mean {:.3g}, median {:.3g}, 95th percentile {:.3g}.", h.total, saved.at("mean").get<double>(), h.quantile(0.5),
                  h.quantile(0.95)));
  return chart;
}

std::string verdict_section(const json& r) {
  const auto nails_per_test = whole(r.at("scenario").at("feed").at("nails"), "scenario.feed.nails", 1, 1000000000);
  const auto& p = r.at("pass_probability");
  if (r.at("verdict") == "invalid") {
    // No verdict for a test that did not really happen: say why, and nothing else.
    std::string o = "<section class=\"verdict fail\" id=\"verdict\">\n";
    o += fmt::format(
        "<p class=\"verdict-line\"><span class=\"caps\">{}</span>: no SAE J232 verdict. The simulated test did not "
        "really happen, so its numbers below describe a broken run, not the mower.</p>\n<ul>\n",
        number("verdict", r.at("verdict"), "{}"));
    for (const auto& reason : r.at("invalid_because")) o += fmt::format("<li>{}</li>\n", escape(reason.get<std::string>()));
    return o + "</ul>\n</section>\n";
  }
  std::string o = fmt::format("<section class=\"verdict {}\" id=\"verdict\">\n", r.at("verdict") == "passes" ? "pass" : "fail");
  // The verdict line carries the estimate the verdict rests on, named; the other follows.
  const auto& e = r.at("pass_probability_exact");
  const bool every_nail = r.at("verdict_basis").at("name") == "every_nail";
  const std::string replicates_sentence =
      fmt::format("{} of {} simulated tests (replicates of {}-nail feeds) met all four criteria: P(pass one test) = {} (95 % interval {} to {}, Wilson).",
                  number("replicates_passed", r.at("replicates_passed"), "{}"), number("replicates", r.at("replicates"), "{}"), nails_per_test,
                  number("pass_probability.estimate", p.at("estimate"), "{:.3f}"), number("pass_probability.low", p.at("low"), "{:.3f}"),
                  number("pass_probability.high", p.at("high"), "{:.3f}"));
  const std::string exact_sentence =
      e.value("computed", false)
          ? fmt::format("From every nail rather than every test: P(pass) = {} (95 % interval {} to {}), the exact probability that a "
                        "{}-nail feed stays within all four limits when each feed station's nails make each combination of marks as "
                        "often as the run's nails did (interval by Bayesian bootstrap).",
                        number("pass_probability_exact.estimate", e.at("estimate"), "{:.3f}"),
                        number("pass_probability_exact.low", e.at("low"), "{:.3f}"), number("pass_probability_exact.high", e.at("high"), "{:.3f}"),
                        nails_per_test)
          : fmt::format("P(pass) from every nail was not computed: {}.", escape(e.value("why_not", std::string())));
  const std::string lead = every_nail ? "P(pass) from every nail" : "P(pass one test)";
  const auto& lead_json = every_nail ? e : p;
  const std::string key = every_nail ? "pass_probability_exact." : "pass_probability.";
  o += fmt::format(
      "<p class=\"verdict-line\"><span class=\"caps\">{}</span> SAE J232 (as simulated): "
      "{} = {} (95 % interval {} to {}); required ≥ {}.</p>\n",
      number("verdict", r.at("verdict"), "{}"), lead, number(key + "estimate", lead_json.at("estimate"), "{:.3f}"),
      number(key + "low", lead_json.at("low"), "{:.3f}"), number(key + "high", lead_json.at("high"), "{:.3f}"),
      number("required_pass_probability", r.at("required_pass_probability"), "{:.2f}"));
  o += fmt::format("<p>{} {}</p>\n",
                   r.at("verdict_settled").get<bool>() ? "The verdict is settled: the whole 95 % interval lies on one side of the required probability."
                               : "<strong>Not settled:</strong> the 95 % interval straddles the required probability; run more "
                                 "replicates (or set run.until_settled) before filing.",
                   fmt::format("The verdict rests on {} ({}).", every_nail ? "the exact estimate from every nail" : "the share of replicates that passed",
                               escape(r.at("verdict_basis").at("why").get<std::string>())));
  o += fmt::format("<p>{}</p>\n<p>{}</p>\n", every_nail ? exact_sentence : replicates_sentence, every_nail ? replicates_sentence : exact_sentence);
  const json& stop = r.at("stop_rule");
  if (!stop.is_null()) {
    const std::string stopped_by = stop.at("stopped_by").get<std::string>();
    o += fmt::format("<p>Stop rule: {} after {} replicates, the verdict's interval looked at {} times (batches growing by half the "
                     "replicates so far). A run stopped when its interval first met the rule covers a little less often than a "
                     "fixed-size run's; so few looks keep that small.</p>\n",
                     stopped_by == "settled"             ? "settled"
                     : stopped_by == "target_half_width" ? "the interval as narrow as run.target_half_width"
                                                          : "<strong>not met</strong>: stopped at run.max_replicates",
                     count_of(r.at("replicates"), "replicates"), count_of(stop.at("looks"), "stop_rule.looks"));
  }
  if (!r.at("warnings").empty()) {
    o += "<p><strong>Before filing, note:</strong></p>\n<ul class=\"warnings\">\n";
    for (const auto& w : r.at("warnings")) o += fmt::format("<li>{}</li>\n", escape(w.get<std::string>()));
    o += "</ul>\n";
  }
  o += "</section>\n";
  return o;
}

std::string criteria_section(const json& r) {
  std::string o = "<section id=\"criteria\">\n<h2>1. The four criteria</h2>\n";
  o += fmt::format(
      "<p>Each criterion limits one kind of mark as a share of {}; a simulated test passes when all four hold. "
      "Shares are over replicates; P(pass) is the share of replicates in which the criterion held, with its "
      "Wilson 95 % interval.</p>\n",
      r.at("denominator") == "marks" ? "all marks (hits plus punctures)" : "the nails fed");
  HtmlTable criteria("numbers", {"criterion", "limit", "mean share", "5–95 % of tests", "P(criterion passes)", ""});
  for (std::size_t c = 0; c < r.at("criteria").size(); ++c) {
    const auto& cj = r.at("criteria")[c];
    const std::string k = fmt::format("criteria.{}.", c);
    const bool deciding = cj.at("name") == r.at("deciding_criterion");
    criteria.row({escape(cj.at("name").get<std::string>()), number(k + "limit", cj.at("limit"), "{:.1f}", 100) + " %",
                  number(k + "mean_share", cj.at("mean_share"), "{:.3f}", 100) + " %",
                  fmt::format("{} – {} %", number(k + "share_q05", cj.at("share_q05"), "{:.2f}", 100),
                              number(k + "share_q95", cj.at("share_q95"), "{:.2f}", 100)),
                  fmt::format("{} ({} – {})", number(k + "pass_probability.estimate", cj.at("pass_probability").at("estimate"), "{:.3f}"),
                              number(k + "pass_probability.low", cj.at("pass_probability").at("low"), "{:.3f}"),
                              number(k + "pass_probability.high", cj.at("pass_probability").at("high"), "{:.3f}")),
                  deciding ? "<strong>decides the verdict</strong>" : ""},
                 deciding ? " class=\"deciding\"" : "");
  }
  o += criteria.html();
  o += fmt::format(
      "<p>Counted marks: {} in all, {} per nail fed ({} could not be located: more than four marks from one "
      "nail). SAE J232 counts only marks above the plane of the blade tip circle: marks from {} m up are counted; "
      "{} marks lower on the board were not (greyed on the hit map).</p>\n",
      number("marks", r.at("marks"), "{}"), number("marks_per_nail", r.at("marks_per_nail"), "{:.4f}"),
      number("marks_not_located", r.at("marks_not_located"), "{}"), number("counted_height_m", r.at("counted_height_m"), "{:.3f}"),
      number("marks_below_counted_height", r.at("marks_below_counted_height"), "{}"));
  for (const auto& d : r.at("departures_from_j232"))
    o += fmt::format("<p class=\"warning\"><strong>Departs from SAE J232:</strong> {}.</p>\n", escape(d.get<std::string>()));
  o += "</section>\n";
  return o;
}

std::string histogram_section(const json& r) {
  std::string o = "<section id=\"energies\">\n<h2>3. Speeds and energies</h2>\n";
  Chart speed = histogram_chart(r.at("exit_speed"), "Nail speed leaving the blade", "speed after its last blade contact before anything else (m/s)",
                                "m/s", "struck nails", palette(0));
  const double tip = r.at("tip_speed_m_s").get<double>();
  speed.vline(tip, "#000", fmt::format("blade tip speed {:.1f} m/s", tip));
  o += "<figure>" + speed.svg() +
       fmt::format(
           "<figcaption>Thrown at {} × the blade tip speed on average (5–95 %: {} to {} ×); published speeds of "
           "mower-thrown objects are about 0.8 to 1.4 × tip speed (Chazen and Chamberlain, 1962, as widely "
           "reported).</figcaption></figure>\n",
           number("exit_speed_over_tip_speed.mean", r.at("exit_speed_over_tip_speed").at("mean"), "{:.2f}"),
           number("exit_speed_over_tip_speed.q05", r.at("exit_speed_over_tip_speed").at("q05"), "{:.2f}"),
           number("exit_speed_over_tip_speed.q95", r.at("exit_speed_over_tip_speed").at("q95"), "{:.2f}"));
  // The launch: which way the blade's contacts send the nail, above or below its plane.
  Chart launch = histogram_chart(r.at("launch_elevation_deg"), "Launch elevation", "elevation of the nail's velocity as it leaves the blade (deg)",
                                 "deg", "struck nails", palette(3));
  launch.vline(0, "#000", "blade plane");
  const auto& le = r.at("launch_elevation_deg");
  const auto& cp = r.at("contacts_per_pass");
  o += "<figure>" + launch.svg() +
       fmt::format("<figcaption>Launched at {}° on average (5–95 %: {}° to {}°), from the geometry of the contacts: the edge, its "
                   "bevel, the plate's faces (a spinning nail's end swings into them) and the sail, with friction. Blade contacts "
                   "per pass: {} on average, at most {}.</figcaption></figure>\n",
                   number("launch_elevation_deg.mean", le.at("mean"), "{:.1f}"), number("launch_elevation_deg.q05", le.at("q05"), "{:.1f}"),
                   number("launch_elevation_deg.q95", le.at("q95"), "{:.1f}"), number("contacts_per_pass.mean", cp.at("mean"), "{:.2f}"),
                   number("contacts_per_pass.most", cp.at("most"), "{}"));
  // Kinetic energy along the board's normal at the first arrival; the thresholds
  // depend on how the nail presents itself, so both extremes are drawn.
  Chart energy = histogram_chart(r.at("board_energy"), "Kinetic energy at the board (normal to it)", "normal kinetic energy at the board (J)",
                                 "J", "nails reaching the board", palette(2));
  const json &board = r.at("scenario").at("board"), &nail = r.at("scenario").at("nail");
  const double kp = board.at("puncture_energy_per_width_J_m").get<double>(), f = board.at("hit_fraction").get<double>();
  const double diameter = nail.at("diameter_m").get<double>(), length = nail.at("length_m").get<double>();
  energy.vline(kp * diameter, palette(1), fmt::format("puncture, point first {:.2f} J", kp * diameter));
  energy.vline(f * kp * diameter, palette(4), fmt::format("hit {:.2f} J", f * kp * diameter));
  energy.vline(kp * length, palette(1), fmt::format("puncture, broadside {:.1f} J", kp * length), false);
  energy.vline(f * kp * length, palette(4), fmt::format("hit {:.1f} J", f * kp * length), false);
  o += "<figure>" + energy.svg() +
       "<figcaption>Dashed: thresholds for a nail arriving point first (presenting its shank diameter); solid: broadside "
       "(presenting its length). Between these the threshold follows the presented width.</figcaption></figure>\n";
  Chart per_width = histogram_chart(r.at("board_energy_per_width"), "Energy per presented width at the board",
                                    "normal kinetic energy / presented width (J/m)", "J/m", "nails reaching the board", palette(2));
  per_width.vline(kp, palette(1), fmt::format("puncture {:g} J/m", kp));
  per_width.vline(f * kp, palette(4), fmt::format("hit {:g} J/m", f * kp));
  o += "<figure>" + per_width.svg() +
       "<figcaption>What the board model compares: right of the hit line a nail leaves a hit, right of the puncture line a "
       "puncture.</figcaption></figure>\n";
  o += "</section>\n";
  return o;
}

// Which way the marking nails got out, so the reader sees which path to close.
std::string exits_section(const json& r) {
  const auto& h = r.at("how_nails_leave");
  HtmlTable exits("numbers", {"way out", "struck nails", "share of struck nails", "counted marks", "share of counted marks (95 %)",
                              "where most of its marks left (azimuth)"});
  for (std::size_t i = 0; i < h.at("by_exit").size(); ++i) {
    const auto& e = h.at("by_exit")[i];
    const std::string key = fmt::format("how_nails_leave.by_exit.{}", i);
    std::string band = "&mdash;";
    std::uint64_t most = 0;
    for (std::size_t b = 0; b < e.at("by_exit_azimuth").size(); ++b) {
      const auto& row = e.at("by_exit_azimuth")[b];
      if (count_of(row.at("marks"), "how_nails_leave's marks") > most) {
        most = count_of(row.at("marks"), "how_nails_leave's marks");
        band = fmt::format("{} to {} deg ({} marks)", whole(row.at("from_deg"), "from_deg", -360, 360), whole(row.at("to_deg"), "to_deg", -360, 360),
                           number(fmt::format("{}.by_exit_azimuth.{}.marks", key, b), row.at("marks"), "{}"));
      }
    }
    // The marks' share with its 95 % interval (none when no mark was counted).
    std::string marks_share = number(key + ".share_of_marks", e.at("share_of_marks"), "{:.1f}", 100) + " %";
    if (e.contains("share_of_marks_95") && !e.at("share_of_marks_95").is_null())
      marks_share += fmt::format(" ({}&ndash;{})", number(key + ".share_of_marks_95.low", e.at("share_of_marks_95").at("low"), "{:.1f}", 100),
                                 number(key + ".share_of_marks_95.high", e.at("share_of_marks_95").at("high"), "{:.1f}", 100));
    exits.row({escape(e.at("exit").get<std::string>()), number(key + ".nails", e.at("nails"), "{}"),
               number(key + ".share_of_struck_nails", e.at("share_of_struck_nails"), "{:.2f}", 100) + " %",
               number(key + ".marks", e.at("marks"), "{}"), marks_share, band});
  }
  std::string o = "<section id=\"exits\">\n<h3>How nails leave the deck</h3>\n" + exits.html() +
                  "<p>Counted marks by the number of blade strikes of their nail: ";
  for (std::size_t i = 0; i < h.at("by_strikes").size(); ++i)
    o += fmt::format(
        "{}{}: {} %", i ? ", " : "", h.at("by_strikes")[i].at("strikes").get<std::string>(),
        number(fmt::format("how_nails_leave.by_strikes.{}.share_of_marks", i), h.at("by_strikes")[i].at("share_of_marks"), "{:.1f}", 100));
  o += ". By the first surface touched after the first strike: ";
  bool first = true;
  for (std::size_t i = 0; i < h.at("by_first_surface").size(); ++i) {
    const auto& f = h.at("by_first_surface")[i];
    if (count_of(f.at("marks"), "how_nails_leave's marks") == 0) continue;
    o += fmt::format("{}{}: {} %", first ? "" : ", ", escape(f.at("first_surface").get<std::string>()),
                     number(fmt::format("how_nails_leave.by_first_surface.{}.share_of_marks", i), f.at("share_of_marks"), "{:.1f}", 100));
    first = false;
  }
  if (first) o += "no counted marks";
  o += ". Intervals: Wilson's 95 % for the share of marks (each nail marks at most once; nails are drawn independently). "
       "The way out is the nail's last crossing of the deck's outline going out, after which it stayed out (a nail a guard "
       "turned back in and that left again elsewhere is named by where it finally left); marks.csv gives every mark's trail "
       "(feed station, strikes, speed off the last strike, surfaces touched in order, way out, where it first left, flight "
       "time).</p>\n</section>\n";
  return o;
}

std::string fates_section(const json& r) {
  HtmlTable fates("numbers", {"fate", "nails", "share of nails fed", ""});
  static const std::vector<std::pair<std::string, std::string>> names = {
      {"not_struck", "not struck by the blade"},
      {"contained_by_housing", "contained by the housing (at rest under the deck)"},
      {"stopped_by_guard", "stopped by a guard"},
      {"reached_board_unmarked", "reached the board without marking it"},
      {"marked_board", "marked the board where J232 counts (hit or puncture)"},
      {"marked_below_counted_height", "marked the board only below the blade plane (not counted)"},
      {"over_board", "went over or past the board"},
      {"at_rest_short_of_board", "came to rest outside the mower, short of the board"},
      {"cut_off", "cut off still moving by the run's time, bounce or step limit"}};
  for (const auto& [key, label] : names) {
    const auto& f = r.at("fates").at(key);
    const double share = f.at("fraction").get<double>();
    fates.row({label, number("fates." + key + ".nails", f.at("nails"), "{}"),
               number("fates." + key + ".fraction", f.at("fraction"), "{:.2f}", 100) + " %",
               fmt::format("<span class=\"bar\" style=\"width:{:.1f}px\"></span>", 240 * share)});
  }
  const auto& k = r.at("strikes_per_struck_nail");
  std::string o = "<section id=\"fates\">\n<h2>4. Where the nails went</h2>\n" + fates.html();
  o += fmt::format(
      "<p>{} nails fed in all, {} struck. The turning blade is part of the scene: a nail "
      "that comes back into its disc is struck again. Blade strikes per struck nail: {} on average; {} % were "
      "struck more than once (at most {} times).</p>\n</section>\n",
      number("nails_fed", r.at("nails_fed"), "{}"), number("nails_struck", r.at("nails_struck"), "{}"),
      number("strikes_per_struck_nail.mean", k.at("mean"), "{:.4f}"),
      number("strikes_per_struck_nail.share_struck_again", k.at("share_struck_again"), "{:.2f}", 100),
      number("strikes_per_struck_nail.most", k.at("most"), "{}"));
  return o + exits_section(r);
}

// The scenario echo flattened to dotted keys: every value the run used.
void flatten(const json& j, const std::string& prefix, std::vector<std::pair<std::string, std::string>>& rows) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) flatten(v, prefix.empty() ? k : prefix + "." + k, rows);
  } else if (j.is_array() && !j.empty() && (j.front().is_object() || j.front().is_array())) {
    for (std::size_t i = 0; i < j.size(); ++i) flatten(j[i], fmt::format("{}[{}]", prefix, i + 1), rows);
  } else if (j.is_number_float()) {
    rows.emplace_back(prefix, fmt::format("{:.6g}", j.get<double>()));
  } else if (j.is_string()) {
    rows.emplace_back(prefix, j.get<std::string>());
  } else {
    rows.emplace_back(prefix, j.dump());
  }
}

std::string scenario_section(const json& r) {
  std::vector<std::pair<std::string, std::string>> rows;
  flatten(r.at("scenario"), "", rows);
  auto keys = HtmlTable::without_header("keys");
  for (const auto& [k, v] : rows) keys.row({escape(k), escape(v)});
  return "<section id=\"scenario\">\n<h2>5. The scenario as run</h2>\n<p>Every value the run used, defaults filled in, "
         "SI units (the unit is in each key's name).</p>\n" +
         keys.html() + "</section>\n";
}

std::string assumptions_section(const json& r) {
  HtmlTable assumptions("", {"assumption", "source"});
  for (const auto& x : r.at("assumptions")) assumptions.row({escape(x.at("assumption").get<std::string>()), escape(x.at("source").get<std::string>())});
  std::string o = "<section id=\"assumptions\">\n<h2>6. Assumptions and their sources</h2>\n" + assumptions.html();
  o += fmt::format("<p>Denominator of the shares: {}.</p>\n</section>\n", number("denominator", r.at("denominator"), "{}"));
  return o;
}

std::string provenance_section(const json& r) {
  const auto& p = r.at("provenance");
  auto keys = HtmlTable::without_header("keys");
  keys.row({"program", "j232 " + escape(p.at("version").get<std::string>())})
      .row({"git revision", escape(p.at("git_revision").get<std::string>())})
      .row({"scenario file", escape(r.at("scenario").at("file").get<std::string>())})
      .row({"seed", number("provenance.seed", p.at("seed"), "{}")})
      .row({"replicates", number("replicates", r.at("replicates"), "{}")})
      .row({"threads", number("provenance.threads", p.at("threads"), "{}")})
      .row({"wall time", number("provenance.wall_time_s", p.at("wall_time_s"), "{:.2f}") + " s"})
      .row({"date (UTC)", escape(p.at("date").get<std::string>())});
  std::string o = "<section id=\"provenance\">\n<h2>7. Provenance</h2>\n" + keys.html();
  o += "<p>The same scenario, seed and replicates give the same results, bit for bit, on any number of "
       "threads; only this section changes between runs.</p>\n</section>\n";
  return o;
}

}  // namespace

std::string compliance_report_html(const json& r) {
  const std::string title = r.at("scenario").at("title").get<std::string>();
  std::string o = page_head("SAE J232 assessment: " + title);
  o += fmt::format("<header><h1>SAE J232 thrown-object assessment (simulated)</h1>\n<p class=\"sub\">{} — <code>{}</code></p></header>\n",
                   escape(title), escape(r.at("scenario").at("file").get<std::string>()));
  o += verdict_section(r);
  o += criteria_section(r);
  o += drivers_html(r);
  if (r.contains("uncertainty")) o += uncertainty_summary_html(r);
  o += "<section id=\"hit-map\">\n<h2>2. Where the marks are</h2>\n";
  o += "<figure>" + hit_map_svg(r) +
       "<figcaption>The target board unrolled around the spindle: azimuth 0 is straight ahead, 90 to the left. The blade plane "
       "and the feed stations' azimuths are drawn for reference. Grey marks lie below the blade plane: SAE J232 does not "
       "count them.</figcaption></figure>\n";
  o += "<figure>" + plan_view_svg(r) + "<figcaption>Seen from above.</figcaption></figure>\n";
  if (r.contains("trajectories"))
    o += "<h3>Paths of chosen nails</h3>\n<figure>" + trajectories_plan_svg(r) + "</figure>\n<figure>" + trajectories_side_svg(r) +
         "</figure>\n";
  o += "</section>\n";
  o += histogram_section(r);
  o += fates_section(r);
  o += scenario_section(r);
  o += assumptions_section(r);
  o += provenance_section(r);
  o += page_foot();
  return o;
}

}  // namespace j232::report
