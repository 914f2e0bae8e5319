#include "report/result_files.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fmt/format.h>
#include <stdexcept>
#include <string_view>

#include "assess/model_version.hpp"
#include "assess/statistics.hpp"
#include "report/board_views.hpp"
#include "report/scenario_json.hpp"
#include "report/text_safety.hpp"
#include "units/quantity.hpp"

namespace j232::report {

namespace {
using json = nlohmann::ordered_json;

json interval_json(const assess::Interval& i) {
  return {{"estimate", i.estimate}, {"low", i.low}, {"high", i.high}, {"confidence", 0.95}, {"method", "Wilson score"}};
}

// P(pass) from every nail (assess/exact_pass.hpp), or why it was not computed.
// Which stop rule ran, how many times it looked and what stopped it.
json stop_rule_json(const scenario::RunSpec& run, const assess::Assessment& a) {
  if (!run.target_half_width && !run.until_settled) return nullptr;
  return {{"target_half_width", run.target_half_width ? json(*run.target_half_width) : json(nullptr)},
          {"until_settled", run.until_settled},
          {"max_replicates", run.max_replicates},
          {"looks", a.looks},
          {"stopped_by", a.stopped_by}};
}

json exact_json(const assess::ExactPass& e) {
  if (!e.computed) return {{"computed", false}, {"why_not", e.not_computed}};
  return {{"computed", true},
          {"estimate", e.value},
          {"low", e.low},
          {"high", e.high},
          {"confidence", 0.95},
          {"method", "exact sum over the counts within the limits, each feed station's nail outcomes as observed; interval by Bayesian "
                     "bootstrap (Dirichlet over the outcome frequencies, a quarter-nail prior on each single mark)"},
          {"bootstrap_draws", e.draws},
          {"states", e.states}};
}

// Each feed station's nails by their counted marks (what the exact P(pass) is computed from).
json outcomes_json(const assess::StationOutcomes& o) {
  json out = json::array();
  for (std::size_t st = 0; st < o.by_station.size(); ++st) {
    const double n = static_cast<double>(o.nails(st));
    json rows = json::array();
    for (const auto& [key, count] : o.by_station[st]) {
      const auto m = assess::marks_of_key(key);
      rows.push_back({{"hits_zone", m[0]},
                      {"punctures_zone", m[1]},
                      {"hits_outside", m[2]},
                      {"punctures_outside", m[3]},
                      {"nails", count},
                      {"probability", n > 0 ? static_cast<double>(count) / n : 0.0}});
    }
    out.push_back({{"station", st + 1}, {"nails", o.nails(st)}, {"outcomes", rows}});
  }
  return out;
}

// Blade strikes per struck nail: the first (the feed's) and every strike after it.
// The histogram's last bin collects every count beyond it, so the largest comes from `most`.
json strikes_json(const assess::Histogram& h, const assess::Largest& most_strikes) {
  const std::uint64_t once = h.counts.size() > 1 ? h.counts[1] : 0;
  std::size_t last_bin = 0;  // the last bin holding any nail (the histogram's last also holds those beyond it)
  for (std::size_t k = 0; k < h.counts.size(); ++k)
    if (h.counts[k] > 0) last_bin = k;
  std::vector<std::uint64_t> counts(h.counts.begin() + 1,
                                    h.counts.begin() + static_cast<std::ptrdiff_t>(std::max<std::size_t>(last_bin, 1)) + 1);
  return {{"mean", h.mean()},
          {"share_struck_again", h.total ? static_cast<double>(h.total - once) / static_cast<double>(h.total) : 0.0},
          {"most", most_strikes.value},
          {"nails_by_strikes_from_1", counts}};
}

json histogram_json(const assess::Histogram& h, const char* unit) {
  return {{"unit", unit},           {"count", h.total},        {"mean", h.mean()},         {"q05", h.quantile(0.05)},
          {"q50", h.quantile(0.5)}, {"q95", h.quantile(0.95)}, {"bin_width", h.bin_width}, {"first_bin_from", h.origin},
          {"counts", h.counts}};
}
// The largest value a histogram of whole counts (bin k holds k) recorded.
int most_in(const assess::Histogram& h) {
  for (std::size_t i = h.counts.size(); i-- > 0;)
    if (h.counts[i]) return static_cast<int>(i);
  return 0;
}
// How the nails left the deck, for the counted marks (the table "How nails leave").
json exits_json(const assess::Assessment& a) {
  const auto& e = a.exits;
  std::uint64_t counted = 0;
  for (const auto& [key, row] : e.marks)
    for (auto n : row) counted += n;
  auto share = [&](std::uint64_t n) { return counted ? static_cast<double>(n) / static_cast<double>(counted) : 0.0; };
  // A share's 95 % interval: each nail marks the board at most once and nails are drawn
  // independently, so a way's marks among the counted ones (its nails among the struck) are
  // binomial: Wilson's interval.
  auto interval = [](std::uint64_t k, std::uint64_t n) {
    if (n == 0) return json(nullptr);
    const assess::Interval w = assess::wilson(k, n);
    return json{{"low", w.low}, {"high", w.high}};
  };
  json by_exit = json::array();
  for (const auto& [key, nails] : e.nails) {
    std::array<std::uint64_t, assess::ExitTable::kBands> row{};
    if (auto it = e.marks.find(key); it != e.marks.end()) row = it->second;
    std::uint64_t marks = 0;
    json bands = json::array();
    for (int b = 0; b < assess::ExitTable::kBands; ++b) {
      marks += row[static_cast<std::size_t>(b)];
      bands.push_back({{"from_deg", -180 + 45 * b},
                       {"to_deg", -135 + 45 * b},
                       {"marks", row[static_cast<std::size_t>(b)]},
                       {"share_of_marks", share(row[static_cast<std::size_t>(b)])}});
    }
    const auto name = a.exit_names.find(key);
    by_exit.push_back({{"exit", name != a.exit_names.end() ? name->second : std::string("unnamed")},
                       {"nails", nails},
                       {"share_of_struck_nails", a.struck ? static_cast<double>(nails) / static_cast<double>(a.struck) : 0.0},
                       {"share_of_struck_nails_95", interval(nails, a.struck)},
                       {"marks", marks},
                       {"share_of_marks", share(marks)},
                       {"share_of_marks_95", interval(marks, counted)},
                       {"by_exit_azimuth", bands}});
  }
  json by_strikes = json::array();
  for (std::size_t i = 0; i < e.marks_by_strikes.size(); ++i)
    by_strikes.push_back({{"strikes", i + 1 == e.marks_by_strikes.size() ? fmt::format("{}+", i + 1) : fmt::format("{}", i + 1)},
                          {"marks", e.marks_by_strikes[i]},
                          {"share_of_marks", share(e.marks_by_strikes[i])}});
  json by_first = json::array();
  for (std::size_t i = 0; i < e.marks_by_first_touch.size(); ++i)
    by_first.push_back({{"first_surface", i < static_cast<std::size_t>(flight::kTouchKinds)
                                              ? std::string(flight::touch_name(static_cast<flight::Touch>(i)))
                                              : std::string("none (straight to the board)")},
                        {"marks", e.marks_by_first_touch[i]},
                        {"share_of_marks", share(e.marks_by_first_touch[i])},
                        {"share_of_marks_95", interval(e.marks_by_first_touch[i], counted)}});
  return {{"counted_marks", counted}, {"by_exit", by_exit}, {"by_strikes", by_strikes}, {"by_first_surface", by_first}};
}

// The first located marks with their nails' trails (marks.csv has them all).
json mark_examples_json(const assess::Assessment& a) {
  json out = json::array();
  for (const auto& m : a.mark_sample) {
    if (out.size() >= 20) break;
    const auto& t = m.trace;
    json path = json::array();
    for (int i = 0; i < std::min(t.touch_count, flight::NailTrace::kMaxTouches); ++i)
      path.push_back(flight::touch_name(t.touches[static_cast<std::size_t>(i)]));
    const auto name = a.exit_names.find(assess::exit_key(t.exit, t.exit_index));
    const auto first = a.exit_names.find(assess::exit_key(t.first_exit, t.first_exit_index));
    out.push_back({{"replicate", m.replicate},
                   {"nail", m.nail},
                   {"point_m", {m.mark.point.x(), m.mark.point.y(), m.mark.point.z()}},
                   {"mark", m.mark.puncture ? "puncture" : "hit"},
                   {"counted", m.mark.counted},
                   {"zone", m.mark.in_zone},
                   {"spindle", m.spindle + 1},
                   {"station", m.station + 1},
                   {"strikes", m.strikes},
                   {"speed_off_last_strike_m_s", t.last_strike_speed},
                   {"path", path},
                   {"path_truncated", t.touch_count > flight::NailTrace::kMaxTouches},
                   {"exit", name != a.exit_names.end() ? name->second : std::string("unnamed")},
                   {"exit_azimuth_deg", t.exit_azimuth / units::degree},
                   {"exit_height_m", t.exit_height},
                   {"first_left_by", first != a.exit_names.end() ? first->second : std::string("unnamed")},
                   {"flight_time_s", m.flight_time}});
  }
  return out;
}
}  // namespace

std::vector<std::string> departures_from_j232(const scenario::Scenario& s) {
  std::vector<std::string> d;
  if (s.criteria.limits_depart_from_j232())
    d.push_back(fmt::format("criteria limits {:g} %, {:g} %, {:g} %, {:g} % instead of SAE J232's 20 %, 0.5 %, 15 %, 5 %",
                            100 * s.criteria.hits_zone, 100 * s.criteria.punctures_zone, 100 * s.criteria.hits_outside,
                            100 * s.criteria.punctures_outside));
  if (s.criteria.counted_height)
    d.push_back(fmt::format("marks counted from {:.0f} mm above ground instead of from the blade plane ({:.0f} mm)",
                            1000 * *s.criteria.counted_height, 1000 * s.blade_plane()));
  return d;
}

json result_json(const scenario::Scenario& s, const assess::Assessment& a, const assess::Summary& sum, const Provenance& p) {
  json criteria = json::array();
  for (const auto& c : sum.criteria)
    criteria.push_back({{"name", c.name},
                        {"limit", c.limit},
                        {"mean_share", c.mean_share},
                        {"share_q05", c.q05},
                        {"share_q50", c.q50},
                        {"share_q95", c.q95},
                        {"pass_probability", interval_json(c.pass)}});
  json fates;
  for (int f = 0; f < flight::kFates; ++f)
    fates[flight::fate_name(static_cast<flight::Fate>(f))] = {
        {"nails", sum.fates[f]}, {"fraction", sum.nails ? static_cast<double>(sum.fates[f]) / static_cast<double>(sum.nails) : 0.0}};
  json cut_off_by = json::object();
  for (int k = 1; k < flight::kCutOffReasons; ++k)
    cut_off_by[flight::cut_off_name(static_cast<flight::CutOff>(k))] = sum.cut_off_by[static_cast<std::size_t>(k)];
  json assumed = json::array();
  for (const auto& x : assumptions(s)) assumed.push_back({{"assumption", x.what}, {"source", x.source}});
  const double tip_speed = s.tip_speed();
  json result = {
      {"program", "j232 run"},
      {"model_version", assess::kModelVersion},
      {"physics_model", assess::kModelPhysics},
      {"verdict", verdict_word(sum)},
      {"verdict_settled", sum.validity.valid && sum.settled},
      // The P(pass) the verdict rests on: which estimate, why, and its value and interval.
      {"verdict_basis",
       {{"name", assess::basis_name(sum.verdict.basis)},
        {"why", sum.verdict.why_basis},
        {"estimate", sum.verdict.pass.estimate},
        {"low", sum.verdict.pass.low},
        {"high", sum.verdict.pass.high}}},
      {"stop_rule", stop_rule_json(s.run, a)},
      {"invalid_because", sum.validity.reasons},
      {"warnings", sum.warnings},
      {"cut_off_by_limit", cut_off_by},
      {"pass_probability", interval_json(sum.pass)},
      {"pass_probability_exact", exact_json(sum.exact)},
      {"nail_outcomes_by_station", outcomes_json(a.outcomes)},
      {"required_pass_probability", sum.required},
      {"deciding_criterion", sum.criteria[sum.deciding].name},
      {"denominator", s.criteria.denominator == scenario::CriteriaSpec::Denominator::Marks ? "marks" : "nails_fed"},
      {"counted_height_m", s.counted_height()},
      {"departures_from_j232", departures_from_j232(s)},
      {"criteria", criteria},
      {"replicates", sum.replicates},
      {"replicates_passed", sum.passed},
      {"nails_fed", sum.nails},
      {"nails_struck", sum.struck},
      {"marks", sum.marks},
      {"marks_per_nail", sum.marks_per_nail},
      {"marks_below_counted_height", a.uncounted_marks},
      {"marks_not_located", a.unlocated_marks},
      {"fates", fates},
      {"exit_speed", histogram_json(a.exit_speed, "m/s")},
      {"tip_speed_m_s", tip_speed},
      {"exit_speed_over_tip_speed",
       {{"mean", a.exit_speed.mean() / tip_speed},
        {"q05", a.exit_speed.quantile(0.05) / tip_speed},
        {"q95", a.exit_speed.quantile(0.95) / tip_speed},
        {"published_range", {assess::kPublishedThrownOverTip[0], assess::kPublishedThrownOverTip[1]}},
        {"published_source", "Chazen and Chamberlain, New England Journal of Medicine, 1962, as widely reported"}}},
      {"launch_elevation_deg", histogram_json(a.launch_elevation, "deg")},
      {"contacts_per_pass",
       {{"mean", a.contacts_per_pass.mean()},
        {"most", a.most_contacts_in_pass.value},
        {"passes", a.contacts_per_pass.total},
        {"passes_by_contacts_from_1",
         std::vector<std::uint64_t>(a.contacts_per_pass.counts.begin() + 1,
                                    a.contacts_per_pass.counts.begin() + std::max(most_in(a.contacts_per_pass), 1) + 1)},
        {"note", fmt::format("a pass: the contacts of one blade edge with the nail until they part (a nail pushed along a face "
                             "touches it many times); the last count holds 32 or more; a pass of more than {} "
                             "(run.max_contacts_per_pass) cuts the nail off",
                             s.run.max_contacts_per_pass)}}},
      {"mark_energy", histogram_json(a.mark_energy, "J")},
      {"contact_radius", histogram_json(a.contact_radius, "m")},
      {"strikes_per_struck_nail", strikes_json(a.strikes, a.most_strikes)},
      {"how_nails_leave", exits_json(a)},
      {"mark_examples", mark_examples_json(a)},
      {"board_energy", histogram_json(a.board_energy, "J")},
      {"board_energy_per_width", histogram_json(a.board_energy_per_width, "J/m")},
      {"scene_queries_per_nail", sum.queries_per_nail},
      {"assumptions", assumed},
      {"scenario", scenario_json(s)},
      // The only part that differs between runs of the same scenario and seed.
      {"provenance",
       {{"version", p.version},
        {"git_revision", p.git_revision},
        {"date", p.date},
        {"inputs_digest", p.inputs_digest},
        {"seed", s.run.seed},
        {"threads", p.threads},
        {"ranks", p.ranks},
        {"wall_time_s", p.wall_seconds},
        {"nails_per_second", p.wall_seconds > 0 ? static_cast<double>(sum.nails) / p.wall_seconds : 0.0}}},
  };
  json files = json::array();
  for (const auto& f : p.files) files.push_back({{"name", f.name}, {"bytes", f.bytes}, {"fnv1a64", f.fnv1a64}});
  result["provenance"]["files"] = files;
  if (!a.trajectories.empty()) {
    // Paths of chosen nails (run --trajectories), only when asked for: they can be large.
    json paths = json::array();
    for (const auto& t : a.trajectories) {
      json points = json::array();
      for (const auto& q : t.points)
        points.push_back({q.x(), q.y(), q.z()});
      paths.push_back(
          {{"replicate", t.replicate}, {"nail", t.nail}, {"why", t.why}, {"fate", flight::fate_name(t.fate)}, {"points_m", points}});
    }
    result["trajectories"] = {
        {"kept", a.trajectories.size()},
        {"notable_not_kept", a.trajectories_not_kept},
        {"note",
         "whole paths of the first struck nails of replicate 0 and of every nail that marked the "
         "operator zone or punctured (up to 100 of each, chosen at random), traced again after the run"},
        {"paths", paths}};
  }
  require_finite(result);
  return result;
}

std::string marks_csv_header() {
  return "replicate,nail,x_m,y_m,z_m,azimuth_deg,height_m,zone,normal_energy_J,mark,counted,"
         "spindle,station,strikes,speed_off_last_strike_m_s,exit,exit_azimuth_deg,exit_height_m,first_left_by,flight_time_s,path\n";
}

void append_marks_csv_row(std::string& out, const assess::MarkRow& m, const assess::Simulator& sim) {
  const auto& p = m.mark.point;
  // Azimuths from -180 to 180 deg (from +x, the direction of travel, toward +y), as the hit map and how_nails_leave give them.
  const double az = azimuth_deg(p.x(), p.y());
  fmt::format_to(std::back_inserter(out), "{},{},{:.4f},{:.4f},{:.4f},{:.2f},{:.4f},{},{:.4f},{},{},", m.replicate, m.nail, p.x(), p.y(),
                 p.z(), az, p.z(), m.mark.in_zone ? "operator_zone" : "outside", m.mark.normal_energy, m.mark.puncture ? "puncture" : "hit",
                 m.mark.counted ? "yes" : "below_counted_height");
  const flight::NailTrace& t = m.trace;
  // The path: what it touched after the first strike, in order ("..." when longer than listed).
  std::string path;
  for (int i = 0; i < std::min(t.touch_count, flight::NailTrace::kMaxTouches); ++i) {
    if (i) path += ';';
    path += flight::touch_name(t.touches[static_cast<std::size_t>(i)]);
  }
  if (t.touch_count > flight::NailTrace::kMaxTouches) path += ";...";
  const double exit_az = t.exit_azimuth / units::degree;
  fmt::format_to(std::back_inserter(out), "{},{},{},{:.3f},{},{:.2f},{:.4f},{},{:.5f},{}\n", m.spindle + 1, m.station + 1, m.strikes,
                 t.last_strike_speed, csv_text_cell(sim.exit_name(t.exit, t.exit_index)), exit_az, t.exit_height,
                 csv_text_cell(sim.exit_name(t.first_exit, t.first_exit_index)), m.flight_time, csv_text_cell(path));
}

const char* verdict_word(const assess::Summary& sum) {
  if (!sum.validity.valid) return "invalid";
  return sum.passes ? "passes" : "fails";
}

namespace {
// The significant digits of a number as JSON writes it ("-0.00123e-5": 3).
int significant_digits(const std::string& number) {
  int digits = 0, zeros = 0;
  bool leading = true;
  for (const char c : number) {
    if (c == 'e' || c == 'E') break;
    if (c < '0' || c > '9') continue;
    if (leading && c == '0') continue;
    leading = false;
    // Trailing zeros after the last non-zero digit are not significant (nor written).
    if (c == '0') ++zeros;
    else digits += zeros + 1, zeros = 0;
  }
  return digits;
}

template <class Json>
void round_numbers(Json& j) {
  if (j.is_number_float()) {
    const double x = j.template get<double>();
    if (std::isfinite(x) && x != 0) {
      char text[32];
      std::snprintf(text, sizeof text, "%.12g", x);
      j = std::strtod(text, nullptr);
    }
  } else if (j.is_structured()) {
    for (auto& v : j) round_numbers(v);
  }
}
// nlohmann's Grisu2 is not always the shortest form: the double nearest 0.182594302 comes out
// as 0.18259430200000001. Each real number of the text longer than 12 significant digits is
// written again in its shortest form (std::to_chars), which after the rounding has at most 12.
std::string shortest_numbers(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) out += text[++i];
      else if (c == '"') in_string = false;
      ++i;
      continue;
    }
    if (c == '"') in_string = true;
    if (c != '-' && (c < '0' || c > '9')) {
      out += c, ++i;
      continue;
    }
    const std::size_t end = text.find_first_not_of("+-0123456789.eE", i);
    const std::string token = text.substr(i, end - i);
    i = end == std::string::npos ? text.size() : end;
    if (token.find_first_of(".eE") == std::string::npos || significant_digits(token) <= 12) {
      out += token;
      continue;
    }
    char shortest[32];
    double value = 0;
    std::from_chars(token.data(), token.data() + token.size(), value);  // (locale-free, as to_chars)
    const auto written = std::to_chars(shortest, shortest + sizeof shortest, value);
    out.append(shortest, written.ptr);
    // A real stays a real when read back (to_chars may write 1e+15 as 1000000000000000).
    if (std::string_view(shortest, static_cast<std::size_t>(written.ptr - shortest)).find_first_of(".eE") == std::string_view::npos) out += ".0";
  }
  return out;
}

template <class Json>
std::string rounded_text(Json j, int indent) {
  round_numbers(j);
  return shortest_numbers(j.dump(indent));
}
}  // namespace

std::string json_text(const nlohmann::json& j, int indent) { return rounded_text(j, indent); }
std::string json_text(const nlohmann::ordered_json& j, int indent) { return rounded_text(j, indent); }
nlohmann::ordered_json as_saved(const nlohmann::ordered_json& j) { return nlohmann::ordered_json::parse(json_text(j)); }

void require_finite(const json& j, const std::string& where) {
  if (j.is_number_float() && !std::isfinite(j.get<double>()))
    throw std::logic_error(fmt::format("result.json: {} is not a finite number", where.empty() ? "a value" : where));
  if (j.is_object())
    for (const auto& [k, v] : j.items()) require_finite(v, where.empty() ? k : where + "." + k);
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) require_finite(j[i], fmt::format("{}[{}]", where, i));
}

std::string summary_text(const scenario::Scenario& s, const assess::Summary& sum) {
  // The verdict's estimate first, the other below it, each saying what it is.
  const auto exact_line = [&]() -> std::string {
    if (!sum.exact.computed) return fmt::format("  P(pass) from every nail: not computed ({})\n", sum.exact.not_computed);
    const bool lead = sum.verdict.basis == assess::Basis::EveryNail;
    return fmt::format("  P(pass) from every nail = {:.3f}  (95 % interval {:.3f} to {:.3f}; required {:.2f}; the exact sum over each station's "
                       "nail outcomes{})\n",
                       sum.exact.value, sum.exact.low, sum.exact.high, sum.required, lead ? "; the verdict's basis: " + sum.verdict.why_basis : "");
  };
  const auto replicates_line = [&]() -> std::string {
    const bool lead = sum.verdict.basis == assess::Basis::Replicates;
    return fmt::format("  P(pass one test) = {:.3f}  (95 % interval {:.3f} to {:.3f}; {} of {} replicates passed{})\n", sum.pass.estimate,
                       sum.pass.low, sum.pass.high, sum.passed, sum.replicates,
                       lead ? fmt::format("; required {:.2f}; the verdict's basis: {}", sum.required, sum.verdict.why_basis) : "");
  };
  std::string out;
  out += fmt::format("{}\n", terminal_safe(s.title));
  if (!sum.validity.valid) {
    out += "NO VERDICT: the simulated test is INVALID\n";
    for (const auto& why : sum.validity.reasons) out += fmt::format("  - {}\n", why);
  } else {
    out += fmt::format("VERDICT: {} SAE J232 (as simulated){}\n", sum.passes ? "PASSES" : "FAILS",
                       sum.settled ? "" : " — not settled: the 95 % interval straddles the required probability");
  }
  if (!sum.validity.valid) {
    out += fmt::format("  nails: {} fed, {} struck; {} cut off. The numbers in the report describe this broken run.\n", sum.nails,
                       sum.struck, sum.fates[static_cast<std::size_t>(flight::Fate::CutOff)]);
    return out;
  }
  if (sum.verdict.basis == assess::Basis::EveryNail)
    out += exact_line() + replicates_line();
  else
    out += replicates_line() + exact_line();
  if (!sum.stopped_by.empty())
    out += fmt::format("  stop rule: {} after {} replicates ({} look{} at the verdict's interval)\n",
                       sum.stopped_by == "settled"             ? "settled"
                       : sum.stopped_by == "target_half_width" ? "interval as narrow as run.target_half_width"
                                                                : "NOT MET: stopped at run.max_replicates",
                       sum.replicates, sum.looks, sum.looks == 1 ? "" : "s");
  out += fmt::format("  {:<20} {:>8} {:>10} {:>17} {:>10}\n", "criterion", "limit", "mean", "5-95 % range", "P(pass)");
  for (int c = 0; c < assess::kCategories; ++c) {
    const auto& cs = sum.criteria[c];
    out +=
        fmt::format("  {:<20} {:>7.1f}% {:>9.2f}% {:>17} {:>10.3f}{}\n", cs.name, 100 * cs.limit, 100 * cs.mean_share,
                    fmt::format("{:.2f}-{:.2f} %", 100 * cs.q05, 100 * cs.q95), cs.pass.estimate, c == sum.deciding ? "  <- decides" : "");
  }
  out += fmt::format(
      "  nails: {} fed, {} struck ({:.1f} %), {:.3f} counted marks per nail; {} marks below the blade plane not "
      "counted\n",
      sum.nails, sum.struck, sum.nails ? 100.0 * static_cast<double>(sum.struck) / static_cast<double>(sum.nails) : 0.0, sum.marks_per_nail,
      sum.uncounted_marks);
  const double tip = s.tip_speed();
  out += fmt::format(
      "  thrown at {:.2f} x the blade tip speed ({:.1f} m/s) on average (published thrown-object speeds: "
      "{:g}-{:g} x)\n",
      sum.exit_speed_mean / tip, tip, assess::kPublishedThrownOverTip[0], assess::kPublishedThrownOverTip[1]);
  for (const auto& d : departures_from_j232(s)) out += fmt::format("  DEPARTS FROM SAE J232: {}\n", d);
  for (const auto& w : sum.warnings) out += fmt::format("  WARNING: {}\n", w);
  return out;
}

}  // namespace j232::report
