// Comparing designs with common random numbers (study/compare.hpp).
#include <algorithm>
#include <catch2/catch.hpp>
#include <vector>
#include <string>

#include "scenario/scenario.hpp"
#include "scenario/scenario_reader.hpp"
#include "assess/statistics.hpp"
#include "random/stream.hpp"
#include "assess/bytes.hpp"
#include "assess/paired_runs.hpp"
#include "assess/paired_sums.hpp"
#include "study/compare.hpp"
#include "report/version_comparison.hpp"
#include "scenario/input_error.hpp"
#include <cmath>
#include <array>
#include <fstream>
#include <vector>

using namespace j232;

namespace {
std::string scenario_path(const char* name) { return std::string(J232_SOURCE_DIR) + "/scenarios/" + name; }

// Two paired sums equal, bit for bit, in every sum and count.
void check_same_sums(const assess::PairedSums& a, const assess::PairedSums& b) {
  CHECK(a.sum == b.sum);
  CHECK(a.squares == b.squares);
  CHECK(a.diff == b.diff);
  CHECK(a.diff_squares == b.diff_squares);
  CHECK(a.differing == b.differing);
  CHECK(a.units_differing == b.units_differing);
}
}  // namespace

TEST_CASE("compare: a design against itself differs by exactly nothing", "[compare]") {
  auto s = scenario::read_scenario(scenario_path("highway-pivoted-raised-skirt.toml"));
  s.run.replicates = 40;
  const auto c = study::compare_designs({s, s}, 2);
  REQUIRE(c.versus_first.size() == 1);
  for (int k = 0; k < assess::kCategories; ++k) {
    const auto& d = c.versus_first[0].shares[static_cast<std::size_t>(k)];
    CHECK(d.mean == 0.0);
    CHECK(d.low == 0.0);
    CHECK(d.high == 0.0);
    CHECK(c.designs[0].shares[static_cast<std::size_t>(k)].mean == c.designs[1].shares[static_cast<std::size_t>(k)].mean);
  }
  // ...while independent runs of it would leave a real interval on the outside shares.
  CHECK(c.versus_first[0].independent_half_width[assess::PuncturesOutside] > 0.005);
  // No replicate differs, and the comparison says how many could have: 1 - 0.025^(1/40).
  CHECK(c.versus_first[0].replicates_differing == 0);
  CHECK(c.versus_first[0].differing_at_most == Approx(0.0881).epsilon(0.01));
  // P(pass)'s difference (Newcombe's paired interval) is zero but not zero-wide.
  const auto& p = c.versus_first[0].pass;
  CHECK(p.mean == 0.0);
  CHECK(p.low < -0.01);
  CHECK(p.high > 0.01);
}

TEST_CASE("compare: Newcombe's paired interval is never zero-wide and covers the true difference about 95 % of the time",
          "[compare][statistics]") {
  // No pair differs: an interval about 0 of about the Wilson width of n.
  const auto none = assess::newcombe_paired(30, 0, 0, 10);
  CHECK(none.estimate == 0.0);
  CHECK(none.low < 0.0);
  CHECK(none.high > 0.0);
  // Swapping the designs negates it.
  const auto ab = assess::newcombe_paired(50, 7, 2, 41), ba = assess::newcombe_paired(50, 2, 7, 41);
  CHECK(ab.estimate == Approx(-ba.estimate));
  CHECK(ab.low == Approx(-ba.high));
  CHECK(ab.high == Approx(-ba.low));
  // Coverage: pairs that pass together with probability 0.85, one only with 0.04 and 0.01
  // (difference -0.03), 200 pairs a trial, 4000 trials.
  random::Stream rng(9, 0, 0, random::Purpose::Test);
  int covered = 0;
  const int trials = 4000;
  for (int t = 0; t < trials; ++t) {
    std::uint64_t n[4] = {0, 0, 0, 0};
    for (int i = 0; i < 200; ++i) {
      const double u = rng.uniform();
      ++n[u < 0.85 ? 0 : u < 0.89 ? 1 : u < 0.90 ? 2 : 3];
    }
    const auto i = assess::newcombe_paired(n[0], n[1], n[2], n[3]);
    covered += i.low <= -0.03 && -0.03 <= i.high;
  }
  const double coverage = static_cast<double>(covered) / trials;
  INFO("coverage " << coverage);
  CHECK(coverage > 0.93);
  CHECK(coverage < 0.975);
}

TEST_CASE("compare: common random numbers make a small design change measurable", "[compare][statistics][long]") {
  // Two chain curtains that differ a little in how open they are.
  auto a = scenario::read_scenario(scenario_path("highway-pivoted-raised-skirt-chains.toml"));
  a.run.replicates = 200;
  auto b = a;
  for (auto& g : b.housing.guards) g.openness = 0.3;
  b.file = "more open";
  const auto c = study::compare_designs({a, b}, 2);
  const auto& v = c.versus_first[0];
  for (int k : {assess::HitsOutside, assess::PuncturesOutside}) {
    const auto& d = v.shares[static_cast<std::size_t>(k)];
    const double paired = 0.5 * (d.high - d.low);
    INFO("criterion " << k << ": difference " << d.mean << ", paired +/-" << paired << ", independent +/-"
                      << v.independent_half_width[static_cast<std::size_t>(k)]);
    CHECK(d.mean > 0);                                                            // more open lets more out
    CHECK(d.low > 0);                                                             // and the pairing resolves it
    CHECK(paired < 0.8 * v.independent_half_width[static_cast<std::size_t>(k)]);  // tighter than independent runs
    // The difference is the difference of the designs' means.
    CHECK(d.mean == Approx(c.designs[1].shares[static_cast<std::size_t>(k)].mean - c.designs[0].shares[static_cast<std::size_t>(k)].mean)
                        .margin(1e-12));
  }
  // Both ran with the first's seed and replicates; many replicates differ, so no bound is given.
  CHECK(c.replicates == 200);
  CHECK(v.replicates_differing > 20);
  CHECK(v.differing_at_most == 0.0);
}

TEST_CASE("statistics: Newcombe's interval for two independent proportions, against its formula worked by hand", "[statistics]") {
  // Wilson's interval written out: (p + z^2/2n -+ z sqrt(p(1-p)/n + z^2/4n^2)) / (1 + z^2/n).
  const double z = 1.959963984540054;
  const auto wilson = [&](double k, double n, double& lo, double& hi) {
    const double p = k / n, c = p + z * z / (2 * n), w = z * std::sqrt(p * (1 - p) / n + z * z / (4 * n * n)), d = 1 + z * z / n;
    lo = (c - w) / d, hi = (c + w) / d;
  };
  for (const auto& [k1, n1, k2, n2] : std::vector<std::array<double, 4>>{{48, 80, 56, 70}, {0, 10, 5, 10}, {9, 10, 10, 10}, {4701, 300000, 5100, 300000}}) {
    double l1, u1, l2, u2;
    wilson(k1, n1, l1, u1), wilson(k2, n2, l2, u2);
    const double p1 = k1 / n1, p2 = k2 / n2, d = p2 - p1;
    const auto got = assess::newcombe_independent(static_cast<std::uint64_t>(k1), static_cast<std::uint64_t>(n1), static_cast<std::uint64_t>(k2),
                                                  static_cast<std::uint64_t>(n2));
    CHECK(got.estimate == Approx(d));
    CHECK(got.low == Approx(d - std::sqrt((p2 - l2) * (p2 - l2) + (u1 - p1) * (u1 - p1))).margin(1e-12));
    CHECK(got.high == Approx(d + std::sqrt((u2 - p2) * (u2 - p2) + (p1 - l1) * (p1 - l1))).margin(1e-12));
    CHECK(got.low < d);
    CHECK(got.high > d);
  }
}

TEST_CASE("compare with an earlier result: itself moves nothing; a changed model, verdict and share are named", "[compare][versions]") {
  const std::string file = std::string(J232_SOURCE_DIR) + "/reports/highway-pivoted/result.json";
  const auto before = report::read_result_file(file);
  SECTION("itself") {
    const auto c = report::compare_results(before, file, before, file);
    CHECK(c["identical"].get<bool>());
    CHECK(c["same_model"].get<bool>());
    CHECK_FALSE(c["verdict_changed"].get<bool>());
    REQUIRE(c["what_moved"].size() == 1);
    CHECK(c["what_moved"][0].get<std::string>().rfind("nothing: the same model and seed", 0) == 0);
    for (const auto& k : c["criteria"]) CHECK_FALSE(k["moved"].get<bool>());
    CHECK(report::version_comparison_html(c).find("What moved") != std::string::npos);
  }
  SECTION("a later version that moved") {
    auto now = before;
    now["model_version"] = now["model_version"].get<int>() + 1;
    now["verdict"] = "fails";
    now["replicates_passed"] = 1500;
    // punctures outside up by half a point (1 500 nails of 300 000); hits outside by a hair.
    const double fed = now["nails_fed"].get<double>();
    for (auto& k : now["criteria"]) {
      if (k["name"] == "punctures_outside") k["mean_share"] = k["mean_share"].get<double>() + 1500 / fed;
      if (k["name"] == "hits_outside") k["mean_share"] = k["mean_share"].get<double>() + 3 / fed;
    }
    const auto c = report::compare_results(before, file, now, "later.json");
    CHECK_FALSE(c["identical"].get<bool>());
    CHECK_FALSE(c["same_model"].get<bool>());
    CHECK(c["verdict_changed"].get<bool>());
    CHECK(c["pass_probability"]["moved"].get<bool>());
    for (const auto& k : c["criteria"]) {
      INFO(k["name"]);
      CHECK(k["moved"].get<bool>() == (k["name"] == "punctures_outside"));
      if (k["name"] == "punctures_outside") {
        CHECK(k["now"]["marks"].get<std::uint64_t>() - k["earlier"]["marks"].get<std::uint64_t>() == 1500);
        CHECK(k["difference"]["estimate"].get<double>() == Approx(0.005));
      }
    }
    std::string words;
    for (const auto& m : c["what_moved"]) words += m.get<std::string>() + "\n";
    CHECK(words.find("the physics changed") != std::string::npos);
    CHECK(words.find("the verdict changed: passes → fails") != std::string::npos);
    CHECK(words.find("punctures_outside") != std::string::npos);
    CHECK(words.find("hits_outside") == std::string::npos);
  }
  SECTION("the same counts under another limit or another criterion are not 'nothing moved'") {
    auto now = before;
    now["criteria"][0]["limit"] = now["criteria"][0]["limit"].get<double>() * 2;
    auto renamed = now["criteria"][1];
    renamed["name"] = "a_new_criterion";
    now["criteria"].push_back(renamed);
    const auto c = report::compare_results(before, file, now, "later.json");
    CHECK_FALSE(c["identical"].get<bool>());
    std::string words;
    for (const auto& m : c["what_moved"]) words += m.get<std::string>() + "\n";
    CHECK(words.find("nothing") == std::string::npos);
    CHECK(words.find("the limit of " + before["criteria"][0]["name"].get<std::string>() + " changed") != std::string::npos);
    CHECK(words.find("criterion a_new_criterion is newly judged") != std::string::npos);
  }
  SECTION("shares of marks have no count behind them: refused") {
    auto marks = before;
    marks["denominator"] = "marks";
    const std::string path = std::string(J232_BINARY_DIR) + "/result-denominator-marks.json";
    std::ofstream(path) << marks.dump();
    try {
      report::read_result_file(path);
      FAIL("a result with shares of marks was read");
    } catch (const scenario::InputError& e) {
      CHECK(std::string(e.what()).find("denominator") != std::string::npos);
    }
  }
  SECTION("not a result") {
    const std::string hazard = std::string(J232_SOURCE_DIR) + "/reports/hazard-deck-72in-lawn-stones/hazard.json";
    try {
      report::read_result_file(hazard);
      FAIL("a hazard.json was read as a result");
    } catch (const scenario::InputError& e) {
      CHECK(std::string(e.what()).find("hazard.json") != std::string::npos);
    }
    CHECK_THROWS_AS(report::read_result_file(std::string(J232_SOURCE_DIR) + "/scenarios/highway-pivoted.toml"), scenario::InputError);
    CHECK_THROWS_AS(report::read_result_file("/nonexistent/result.json"), scenario::InputError);
  }
}

TEST_CASE("compare: the paired sums give a comparison's figures as worked directly from its replicates' rows", "[compare][statistics]") {
  // Three designs, 23 replicates of made-up rows: shares on a grid of 1/150 (as a replicate's
  // are) and pass indicators that agree and disagree in every way.
  random::Stream rng(7, 0, 0, random::Purpose::Test);
  std::vector<study::DesignRecord> designs(3);
  for (auto& d : designs) d.per_replicate.resize(23);
  for (std::size_t r = 0; r < 23; ++r)
    for (std::size_t d = 0; d < 3; ++d) {
      auto& row = designs[d].per_replicate[r];
      for (std::size_t k = 0; k < row.size() - 1; ++k)
        row[k] = (d == 1 && r % 3 == 0) ? designs[0].per_replicate[r][k] : std::floor(rng.uniform() * 9) / 150;
      row.back() = d == 1 && r % 4 != 0 ? designs[0].per_replicate[r].back() : (rng.uniform() < 0.6 ? 1.0 : 0.0);
    }
  const auto c = study::compare_records(designs, 7);
  REQUIRE(c.versus_first.size() == 2);
  for (std::size_t d = 1; d < 3; ++d) {
    const auto& v = c.versus_first[d - 1];
    std::uint64_t differing = 0, both = 0, only_first = 0, only_other = 0, neither = 0;
    for (std::size_t r = 0; r < 23; ++r) {
      const auto& a = designs[0].per_replicate[r];
      const auto& b = designs[d].per_replicate[r];
      differing += a != b ? 1 : 0;
      const bool x = a.back() > 0.5, y = b.back() > 0.5;
      (x && y ? both : x ? only_first : y ? only_other : neither) += 1;
    }
    CHECK(v.replicates_differing == differing);
    const auto nc = assess::newcombe_paired(both, only_first, only_other, neither);
    CHECK(v.pass.mean == nc.estimate);
    CHECK(v.pass.low == nc.low);
    CHECK(v.pass.high == nc.high);
    for (std::size_t k = 0; k < assess::kCategories; ++k) {
      // The mean difference and its normal interval (sample variance, n - 1).
      double sum = 0, squares = 0;
      for (std::size_t r = 0; r < 23; ++r) {
        const double delta = designs[d].per_replicate[r][k] - designs[0].per_replicate[r][k];
        sum += delta, squares += delta * delta;
      }
      const double mean = sum / 23, half = 1.959963984540054 * std::sqrt((squares - sum * sum / 23) / 22 / 23);
      CHECK(v.shares[k].mean == Approx(mean).margin(1e-15));
      CHECK(v.shares[k].low == Approx(std::max(-1.0, mean - half)).margin(1e-12));
      CHECK(v.shares[k].high == Approx(std::min(1.0, mean + half)).margin(1e-12));
    }
  }
}

TEST_CASE("compare: paired sums merged chunk by chunk, or sent between ranks, equal the sums added unit by unit", "[compare][statistics]") {
  // Integer-valued figures: every sum exact, so any grouping gives the same bits.
  const std::size_t designs = 3, figures = 4;
  random::Stream rng(11, 0, 0, random::Purpose::Test);
  std::vector<std::vector<double>> units(40, std::vector<double>(designs * figures));
  for (auto& y : units)
    for (auto& v : y) v = std::floor(rng.uniform() * 3);
  assess::PairedSums whole(designs, figures), merged(designs, figures);
  for (const auto& y : units) whole.add(y.data());
  for (std::size_t start = 0; start < units.size(); start += 7) {
    assess::PairedSums chunk(designs, figures);
    for (std::size_t i = start; i < std::min(units.size(), start + 7); ++i) chunk.add(units[i].data());
    assess::ByteWriter w;
    chunk.pack(w);
    const std::string bytes = w.take();
    assess::PairedSums received(designs, figures);
    assess::ByteReader r(bytes);
    received.unpack(r);
    CHECK(r.done());
    merged.merge(received);
  }
  CHECK(merged.units == 40);
  check_same_sums(merged, whole);
  // Counted directly: the units where design 2's figure 1 differs from the first's, and where any does.
  std::uint64_t one = 0, any = 0;
  for (const auto& y : units) {
    one += y[2 * figures + 1] != y[1] ? 1 : 0;
    bool a = false;
    for (std::size_t j = 0; j < figures; ++j) a = a || y[2 * figures + j] != y[j];
    any += a ? 1 : 0;
  }
  CHECK(whole.differing[whole.versus_first(2, 1)] == one);
  CHECK(whole.units_differing[1] == any);
  // A message of another shape is refused, not read as garbage.
  assess::ByteWriter w;
  whole.pack(w);
  const std::string bytes = w.take();
  assess::PairedSums other(2, figures);
  assess::ByteReader r(bytes);
  CHECK_THROWS(other.unpack(r));
}

TEST_CASE("compare: the one paired driver adds every design's units in order, in blocks, whatever the segment", "[compare]") {
  // Three designs, two figures, 37 units: each unit's own figures a small whole count (so
  // designs often agree), its value that count times a weight of its design.
  constexpr std::size_t designs = 3, figures = 2;
  constexpr std::uint64_t units = 37, block = 4;
  const auto own = [](std::size_t d, std::uint64_t u, std::size_t j) {
    random::Stream rng(11, u, static_cast<std::uint32_t>(d * figures + j), random::Purpose::Feed);
    return std::floor(3 * rng.uniform());
  };
  const auto weight = [](std::size_t d) { return 0.1 * static_cast<double>(d + 1); };
  // By hand: blocks of 4 units, each block's sums merged in order.
  assess::PairedSums expected(designs, figures);
  for (std::uint64_t start = 0; start < units; start += block) {
    assess::PairedSums part(designs, figures);
    for (std::uint64_t u = start; u < std::min(units, start + block); ++u) {
      double y[designs * figures];
      for (std::size_t d = 0; d < designs; ++d)
        for (std::size_t j = 0; j < figures; ++j) y[d * figures + j] = weight(d) * own(d, u, j);
      part.add(y, [&](std::size_t d, std::size_t j) { return own(d, u, j) != own(0, u, j); });
    }
    expected.merge(part);
  }
  for (const std::uint64_t segment : {std::uint64_t{4}, std::uint64_t{8}, std::uint64_t{40}}) {
    INFO("segment " << segment);
    std::vector<std::pair<std::size_t, std::uint64_t>> runs;  // (design, first) in the order run
    assess::PairedRuns p;
    p.designs = designs, p.figures = figures, p.units = units, p.block = block, p.segment = segment;
    p.run = [&](std::size_t d, std::uint64_t first, std::uint64_t count, const assess::UnitSink& sink) {
      runs.emplace_back(d, first);
      for (std::uint64_t u = first; u < first + count; ++u) {
        const double row[figures] = {own(d, u, 0), own(d, u, 1)};
        sink(u, row);
      }
    };
    p.value = [&](std::size_t d, std::uint64_t, std::size_t, double figure) { return weight(d) * figure; };
    const assess::PairedSums got = assess::run_paired(p);
    CHECK(got.units == units);
    check_same_sums(got, expected);
    // Every design in turn over each segment, the segments in order.
    REQUIRE(runs.size() == designs * ((units + segment - 1) / segment));
    for (std::size_t k = 0; k < runs.size(); ++k) CHECK(runs[k] == std::make_pair(k % designs, (k / designs) * segment));
  }
  // Some units differ and some do not (the check above means something).
  CHECK(expected.units_differing[0] > 0);
  CHECK(expected.units_differing[0] < units);
}
