#include "report/version_comparison.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "assess/statistics.hpp"
#include "report/html_page.hpp"
#include "report/html_table.hpp"
#include "report/svg_chart.hpp"  // escape
#include "scenario/input_error.hpp"

namespace j232::report {

using json = nlohmann::ordered_json;

namespace {

// The value at `key` (dotted) of `r`, or null (by the library's JSON pointer).
const json* find(const json& r, const std::string& key) {
  std::string pointer = "/" + key;
  std::replace(pointer.begin(), pointer.end(), '.', '/');
  const json::json_pointer at(pointer);
  return r.contains(at) ? &r.at(at) : nullptr;
}

json interval_json(const assess::Interval& i) { return {{"estimate", i.estimate}, {"low", i.low}, {"high", i.high}}; }

bool moved(const assess::Interval& d) { return d.low > 0 || d.high < 0; }

std::uint64_t count_of(double share, std::uint64_t of) { return static_cast<std::uint64_t>(std::llround(share * static_cast<double>(of))); }

json side(const json& r, const std::string& file) {
  const auto text = [&](const char* key) -> json {
    const json* v = find(r, key);
    return v && v->is_string() ? *v : json(nullptr);
  };
  const json* version = find(r, "model_version");
  json out = {{"file", file},
              {"title", text("scenario.title")},
              {"scenario_file", text("scenario.file")},
              {"model_version", version && version->is_number_integer() ? *version : json(nullptr)},
              {"physics_model", text("physics_model")},
              {"program_version", text("provenance.version")},
              {"git_revision", text("provenance.git_revision")},
              {"date", text("provenance.date")},
              {"seed", r["provenance"]["seed"]},
              {"replicates", r["replicates"]},
              {"verdict", r["verdict"]}};
  if (const json* e = find(r, "pass_probability_exact"); e && e->value("computed", false))
    out["pass_probability_exact"] = {{"estimate", (*e)["estimate"]}, {"low", (*e)["low"]}, {"high", (*e)["high"]}};
  return out;
}

std::string model_version_words(const json& s) {
  return s["model_version"].is_null() ? "model_version not recorded" : fmt::format("model_version {}", s["model_version"].get<int>());
}

std::string version_words(const json& s) {
  std::string o = model_version_words(s);
  // (fmt, not "literal" + string: GCC 12 warns falsely of an overlapping copy there.)
  if (!s["program_version"].is_null()) o += fmt::format(", j232 {}", s["program_version"].get<std::string>());
  if (!s["git_revision"].is_null()) o += fmt::format(" {}", s["git_revision"].get<std::string>());
  if (!s["date"].is_null()) o += fmt::format(", {}", s["date"].get<std::string>());
  return o;
}

std::string points(double v) { return fmt::format("{:+.3f}", 100 * v); }

}  // namespace

json read_result_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw scenario::InputError(path, std::nullopt, "", "", "a result.json that can be read");
  std::stringstream text;
  text << in.rdbuf();
  json r = json::parse(text.str(), nullptr, false);
  if (r.is_discarded() || !r.is_object()) throw scenario::InputError(path, std::nullopt, "", "", "a result.json (JSON) as j232 run writes it");
  const auto need = [&](const char* key, bool ok) {
    if (!ok) {
      const json* v = find(r, key);
      throw scenario::InputError(path, std::nullopt, key, v ? v->dump() : "(missing)",
                                 "the key as j232 run writes it in result.json (a J232 test's result, not a field's hazard.json)");
    }
  };
  const auto is = [&](const char* key, auto test) {
    const json* v = find(r, key);
    return v && test(*v);
  };
  need("program", is("program", [](const json& v) { return v.is_string() && v.get<std::string>().rfind("j232", 0) == 0; }));
  need("verdict", is("verdict", [](const json& v) { return v.is_string(); }));
  need("replicates", is("replicates", [](const json& v) { return v.is_number_unsigned() && v.get<std::uint64_t>() > 0; }));
  need("replicates_passed", is("replicates_passed", [&](const json& v) { return v.is_number_unsigned() && v.get<std::uint64_t>() <= r["replicates"].get<std::uint64_t>(); }));
  need("nails_fed", is("nails_fed", [](const json& v) { return v.is_number_unsigned() && v.get<std::uint64_t>() > 0; }));
  need("provenance.seed", is("provenance.seed", [](const json& v) { return v.is_number_unsigned(); }));
  // A share of marks (criteria.denominator = "marks") is a mean of per-replicate ratios: no
  // binomial count can be rebuilt from it, so such results are not compared.
  if (const json* d = find(r, "denominator"); d && *d != "nails_fed")
    throw scenario::InputError(path, std::nullopt, "denominator", d->dump(),
                               "\"nails_fed\": a result whose shares are of marks cannot be compared this way (its per-criterion "
                               "counts are not recorded); compare its scenarios with j232 compare A.toml B.toml instead");
  need("criteria", is("criteria", [](const json& v) {
         if (!v.is_array() || v.empty()) return false;
         for (const auto& c : v)
           if (!c.is_object() || !c.contains("name") || !c["name"].is_string() || !c.contains("limit") || !c["limit"].is_number() ||
               !c.contains("mean_share") || !c["mean_share"].is_number() || !(c["mean_share"].get<double>() >= 0) || !(c["mean_share"].get<double>() <= 1))
             return false;
         return true;
       }));
  return r;
}

json compare_results(const json& before, const std::string& before_file, const json& now, const std::string& now_file) {
  json c;
  c["kind"] = "a result compared with an earlier one (j232 compare)";
  c["method"] =
      "the two runs share no per-replicate record, so they are judged as independent samples: each share and P(pass) with "
      "its Wilson interval, each difference (now minus earlier) with Newcombe's hybrid score interval for two independent "
      "proportions (1998, method 10); a difference whose 95 % interval leaves out zero has moved. Runs with the same seed are "
      "positively correlated, so these intervals are conservative: a difference inside one is not evidence that nothing changed";
  c["earlier"] = side(before, before_file);
  c["now"] = side(now, now_file);
  c["same_model"] = c["earlier"]["model_version"] == c["now"]["model_version"] && c["earlier"]["physics_model"] == c["now"]["physics_model"];
  c["same_seed"] = c["earlier"]["seed"] == c["now"]["seed"];
  c["verdict_changed"] = before["verdict"] != now["verdict"];
  std::vector<std::string> moves;
  if (!c["same_model"].get<bool>())
    moves.push_back(fmt::format("the physics changed between them ({} → {})", model_version_words(c["earlier"]), model_version_words(c["now"])));
  if (c["verdict_changed"].get<bool>())
    moves.push_back(fmt::format("the verdict changed: {} → {}", before["verdict"].get<std::string>(), now["verdict"].get<std::string>()));

  const std::uint64_t r1 = before["replicates"], r2 = now["replicates"];
  const std::uint64_t p1 = before["replicates_passed"], p2 = now["replicates_passed"];
  const std::uint64_t n1 = before["nails_fed"], n2 = now["nails_fed"];
  const assess::Interval pass_d = assess::newcombe_independent(p1, r1, p2, r2);
  c["pass_probability"] = {{"earlier", interval_json(assess::wilson(p1, r1))},
                           {"now", interval_json(assess::wilson(p2, r2))},
                           {"difference", interval_json(pass_d)},
                           {"moved", moved(pass_d)}};
  if (moved(pass_d)) moves.push_back(fmt::format("P(pass) of the replicates: {:.3f} → {:.3f} ({:+.3f}, 95 % {:+.3f} to {:+.3f})", static_cast<double>(p1) / static_cast<double>(r1),
                                                 static_cast<double>(p2) / static_cast<double>(r2), pass_d.estimate, pass_d.low, pass_d.high));
  bool identical = p1 == p2 && r1 == r2 && n1 == n2 && !c["verdict_changed"].get<bool>();
  json criteria = json::array();
  for (const auto& b : before["criteria"]) {
    const json* match = nullptr;
    for (const auto& n : now["criteria"])
      if (n["name"] == b["name"]) match = &n;
    if (!match) {
      moves.push_back(fmt::format("criterion {} is no longer judged", b["name"].get<std::string>()));
      identical = false;
      continue;
    }
    const std::uint64_t k1 = count_of(b["mean_share"], n1), k2 = count_of((*match)["mean_share"], n2);
    identical = identical && k1 == k2;
    const assess::Interval d = assess::newcombe_independent(k1, n1, k2, n2);
    const auto share = [](std::uint64_t k, std::uint64_t n) {
      const assess::Interval w = assess::wilson(k, n);
      return json{{"share", w.estimate}, {"low", w.low}, {"high", w.high}, {"marks", k}};
    };
    criteria.push_back({{"name", b["name"]},
                        {"limit_earlier", b["limit"]},
                        {"limit_now", (*match)["limit"]},
                        {"earlier", share(k1, n1)},
                        {"now", share(k2, n2)},
                        {"difference", interval_json(d)},
                        {"moved", moved(d)}});
    if (b["limit"] != (*match)["limit"]) {
      moves.push_back(fmt::format("the limit of {} changed: {} → {}", b["name"].get<std::string>(), b["limit"].dump(), (*match)["limit"].dump()));
      identical = false;
    }
    if (moved(d))
      moves.push_back(fmt::format("{}: {:.3f} % → {:.3f} % of nails fed ({} points, 95 % {} to {})", b["name"].get<std::string>(),
                                  100 * static_cast<double>(k1) / static_cast<double>(n1), 100 * static_cast<double>(k2) / static_cast<double>(n2),
                                  points(d.estimate), points(d.low), points(d.high)));
  }
  for (const auto& n : now["criteria"]) {
    bool judged_before = false;
    for (const auto& b : before["criteria"]) judged_before = judged_before || b["name"] == n["name"];
    if (!judged_before) {
      moves.push_back(fmt::format("criterion {} is newly judged", n["name"].get<std::string>()));
      identical = false;
    }
  }
  c["criteria"] = criteria;
  c["identical"] = identical;
  if (identical && c["same_model"].get<bool>() && c["same_seed"].get<bool>())
    moves.insert(moves.begin(), "nothing: the same model and seed give the same verdict, P(pass) and counts (a run is deterministic)");
  else if (moves.empty())
    moves.push_back("nothing beyond its interval: every difference's 95 % interval holds zero");
  c["what_moved"] = moves;
  return c;
}

std::string version_comparison_text(const json& c) {
  std::string o;
  for (const char* which : {"earlier", "now"}) {
    const json& s = c[which];
    o += fmt::format("{:<8} {} ({}): {}, {} replicates, seed {}\n", std::string(which) + ":", s["file"].get<std::string>(), version_words(s),
                     s["verdict"].get<std::string>(), s["replicates"].get<std::uint64_t>(), s["seed"].get<std::uint64_t>());
  }
  const json& p = c["pass_probability"];
  o += fmt::format("  P(pass) of the replicates: {:.3f} ({:.3f}-{:.3f}) → {:.3f} ({:.3f}-{:.3f}); difference {:+.3f} ({:+.3f} to {:+.3f})\n",
                   p["earlier"]["estimate"].get<double>(), p["earlier"]["low"].get<double>(), p["earlier"]["high"].get<double>(),
                   p["now"]["estimate"].get<double>(), p["now"]["low"].get<double>(), p["now"]["high"].get<double>(),
                   p["difference"]["estimate"].get<double>(), p["difference"]["low"].get<double>(), p["difference"]["high"].get<double>());
  o += fmt::format("  {:<18} {:>20} {:>20} {:>32}\n", "criterion", "earlier (% of fed)", "now (% of fed)", "difference, points (95 %)");
  for (const auto& k : c["criteria"])
    o += fmt::format("  {:<18} {:>20} {:>20} {:>32}{}\n", k["name"].get<std::string>(), fmt::format("{:.3f}", 100 * k["earlier"]["share"].get<double>()),
                     fmt::format("{:.3f}", 100 * k["now"]["share"].get<double>()),
                     fmt::format("{} ({} to {})", points(k["difference"]["estimate"]), points(k["difference"]["low"]), points(k["difference"]["high"])),
                     k["moved"].get<bool>() ? "  moved" : "");
  o += "What moved:\n";
  for (const auto& m : c["what_moved"]) o += "  - " + m.get<std::string>() + "\n";
  return o;
}

std::string version_comparison_html(const json& c) {
  std::string o = page_head("What moved since an earlier result");
  o += "<h1>What moved since an earlier result</h1>\n";
  o += "<ul>\n";
  for (const auto& m : c["what_moved"]) o += "<li>" + escape(m.get<std::string>()) + "</li>\n";
  o += "</ul>\n";
  HtmlTable runs("numbers", {"", "result", "physics", "verdict", "replicates", "seed", "P(pass) of the replicates (95 %)"});
  for (const char* which : {"earlier", "now"}) {
    const json& s = c[which];
    const std::string key = std::string("pass_probability.") + which;
    runs.row({which, escape(s["file"].get<std::string>()), escape(version_words(s)), escape(s["verdict"].get<std::string>()),
              number(std::string(which) + ".replicates", s["replicates"], "{}"), number(std::string(which) + ".seed", s["seed"], "{}"),
              fmt::format("{} ({}&ndash;{})", number(key + ".estimate", c["pass_probability"][which]["estimate"], "{:.3f}"),
                          number(key + ".low", c["pass_probability"][which]["low"], "{:.3f}"),
                          number(key + ".high", c["pass_probability"][which]["high"], "{:.3f}"))});
  }
  o += runs.html();
  HtmlTable criteria("numbers", {"criterion", "earlier, % of nails fed (95 %)", "now (95 %)", "difference, points (95 %)", ""});
  for (std::size_t i = 0; i < c["criteria"].size(); ++i) {
    const json& k = c["criteria"][i];
    const std::string key = fmt::format("criteria.{}.", i);
    const auto cell = [&](const char* which) {
      return fmt::format("{} ({}&ndash;{})", number(key + which + ".share", k[which]["share"], "{:.3f}", 100),
                         number(key + which + ".low", k[which]["low"], "{:.3f}", 100), number(key + which + ".high", k[which]["high"], "{:.3f}", 100));
    };
    criteria.row({escape(k["name"].get<std::string>()), cell("earlier"), cell("now"),
                  fmt::format("{} ({} to {})", number(key + "difference.estimate", k["difference"]["estimate"], "{:+.3f}", 100),
                              number(key + "difference.low", k["difference"]["low"], "{:+.3f}", 100),
                              number(key + "difference.high", k["difference"]["high"], "{:+.3f}", 100)),
                  k["moved"].get<bool>() ? "moved" : ""});
  }
  o += criteria.html() + "<p>" + escape(c["method"].get<std::string>()) + ".</p>\n";
  o += page_foot();
  return o;
}

}  // namespace j232::report
