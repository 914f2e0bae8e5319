// Board classification, statistics, the replicate judgement, determinism across thread
// counts and chunk order, and an allocation-free per-nail path.
#include <catch2/catch.hpp>

#include "allocation_counter.hpp"
#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "board/board.hpp"
#include "report/compliance_report.hpp"
#include "report/result_files.hpp"
#include "scene/j232_setup.hpp"
#include "scenario/scenario.hpp"

using namespace j232;

namespace {
std::string scenario_path(const char* name) { return std::string(J232_SOURCE_DIR) + "/scenarios/" + name; }
}  // namespace

TEST_CASE("board: mark classification table", "[board]") {
  scenario::BoardSpec b;  // 110 J/m, hits at 0.3 of the puncture energy
  const double L = 0.0508, D = 0.00251;
  const double point_first = board::presented_width(L, D, 1.0), broadside = board::presented_width(L, D, 0.0);
  CHECK(point_first == Approx(D));
  CHECK(broadside == Approx(L));
  CHECK(board::presented_width(L, D, std::cos(0.5)) == Approx(L * std::sin(0.5) + D * std::cos(0.5)));
  struct Row {
    double energy, width;
    board::Mark expected;
  };
  const Row table[] = {
      {0.05, point_first, board::Mark::None},      {0.09, point_first, board::Mark::Hit},
      {0.28, point_first, board::Mark::Puncture},  {1.0, broadside, board::Mark::None},
      {1.7, broadside, board::Mark::Hit},          {5.5, broadside, board::Mark::Hit},
      {5.6, broadside, board::Mark::Puncture},     {10.0, broadside, board::Mark::Puncture},
  };
  for (const auto& r : table) {
    INFO(r.energy << " J over " << r.width * 1e3 << " mm");
    CHECK(board::classify(r.energy, r.width, b) == r.expected);
  }
}

TEST_CASE("statistics: Wilson interval and quantiles", "[statistics]") {
  auto i = assess::wilson(0, 10);
  CHECK(i.low == 0.0);
  CHECK(i.high == Approx(0.2775).epsilon(1e-3));
  i = assess::wilson(5, 10);
  CHECK(i.low == Approx(0.2366).epsilon(1e-3));
  CHECK(i.high == Approx(0.7634).epsilon(1e-3));
  i = assess::wilson(1000, 1000);
  CHECK(i.high == 1.0);
  CHECK(i.low == Approx(0.99617).epsilon(1e-4));
  CHECK(assess::quantile_sorted({1, 2, 3, 4, 5}, 0.5) == 3);
  CHECK(assess::quantile_sorted({1, 2, 3, 4}, 0.5) == 2.5);
  assess::Histogram h(1.0, 10);
  for (int k = 0; k < 100; ++k) h.add(k * 0.05);  // 0 .. 4.95
  CHECK(h.mean() == Approx(2.475));
  CHECK(h.quantile(0.5) == Approx(2.5).margin(0.05));
}

TEST_CASE("judgement: shares of nails fed or of marks against the four limits", "[assess]") {
  assess::ReplicateTally t;
  t.nails = 150;
  t.counts = {30, 0, 10, 7};  // 20 % zone hits (on the limit), 6.7 % outside hits, 4.7 % punctures
  t.marks = 47;
  scenario::CriteriaSpec c;
  auto j = assess::judge(t, c);
  CHECK(j.shares[assess::HitsZone] == Approx(0.2));
  CHECK(j.passes[assess::HitsZone]);
  CHECK(j.passes[assess::PuncturesOutside]);
  CHECK(j.pass);
  t.counts[assess::PuncturesZone] = 1;  // one zone puncture in 150 is 0.67 % > 0.5 %
  CHECK_FALSE(assess::judge(t, c).pass);
  t.counts[assess::PuncturesZone] = 0;
  c.denominator = scenario::CriteriaSpec::Denominator::Marks;  // the literal reading
  j = assess::judge(t, c);
  CHECK(j.shares[assess::HitsZone] == Approx(30.0 / 47));
  CHECK_FALSE(j.pass);
}

TEST_CASE("determinism: the same result, bit for bit, on 1 and 2 threads and in any chunk order", "[assess][determinism]") {
  auto s = scenario::read_scenario(scenario_path("highway-pivoted-chains.toml"));
  s.run.replicates = 48;
  const assess::Simulator sim(s);
  const auto one = assess::run_assessment(sim, 1);
  const auto two = assess::run_assessment(sim, 2);
  const report::Provenance p{"test", "test", "today", "digest", 0, 0};
  const auto sum_one = assess::summarise(one, s.criteria), sum_two = assess::summarise(two, s.criteria);
  const auto json_one = report::result_json(s, one, sum_one, p), json_two = report::result_json(s, two, sum_two, p);
  CHECK(json_one.dump() == json_two.dump());
  CHECK(report::marks_csv(one) == report::marks_csv(two));
  const auto soup = scene::build_scene_soup(s);
  CHECK(report::compliance_report_html(s, one, sum_one, json_one, soup) == report::compliance_report_html(s, two, sum_two, json_two, soup));
  // Replicates run in a different grouping and order give the same tallies.
  assess::Assessment parts;
  assess::run_replicates(sim, 24, 24, parts, nullptr);
  assess::run_replicates(sim, 0, 24, parts, nullptr);
  for (std::size_t r = 0; r < 24; ++r) {
    CHECK(parts.tallies[24 + r].counts == one.tallies[r].counts);
    CHECK(parts.tallies[r].counts == one.tallies[24 + r].counts);
  }
  // Another seed gives another result.
  s.run.seed += 1;
  const assess::Simulator other(s);
  const auto three = assess::run_assessment(other, 2);
  CHECK(report::marks_csv(three) != report::marks_csv(one));
}

TEST_CASE("performance: simulating a nail allocates nothing", "[assess][allocation]") {
  const auto s = scenario::read_scenario(scenario_path("highway-pivoted-chains.toml"));
  const assess::Simulator sim(s);
  (void)sim.simulate(0, 0);  // warm up
  test::allocations::start();
  int struck = 0;
  for (int n = 0; n < 300; ++n) struck += sim.simulate(1, n).flight.fate != flight::Fate::NotStruck;
  const long allocations = test::allocations::stop();
  CHECK(struck > 100);
  CHECK(allocations == 0);
  // The counter works: a vector allocates.
  test::allocations::start();
  std::vector<double> v(10);
  CHECK(test::allocations::stop() == 1);
}

TEST_CASE("stop rule: batches run until the P(pass) interval is narrow enough", "[assess][stop]") {
  auto s = scenario::read_scenario(scenario_path("highway-pivoted-raised-skirt.toml"));
  s.run.replicates = 16;
  s.run.target_half_width = 0.02;
  s.run.max_replicates = 400;
  const assess::Simulator sim(s);
  const auto a = assess::run_assessment(sim, 2);
  const auto sum = assess::summarise(a, s.criteria);
  CHECK(a.tallies.size() % 16 == 0);
  CHECK(a.tallies.size() > 16);  // one batch of 16 cannot reach +/- 0.02
  const bool narrow = 0.5 * (sum.pass.high - sum.pass.low) <= 0.02;
  CHECK((narrow || a.tallies.size() == 400));
  // ...and it stopped at the first batch that was narrow enough.
  assess::Assessment shorter;
  assess::run_replicates(sim, 0, a.tallies.size() - 16, shorter, nullptr);
  const auto before = assess::summarise(shorter, s.criteria);
  CHECK(0.5 * (before.pass.high - before.pass.low) > 0.02);
}
