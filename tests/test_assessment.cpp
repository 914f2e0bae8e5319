// Board classification, statistics, the replicate judgement, determinism across thread
// counts and chunk order, and an allocation-free per-nail path.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "allocation_counter.hpp"
#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "assess/trajectories.hpp"
#include "board/board.hpp"
#include "report/board_views.hpp"
#include "report/compliance_report.hpp"
#include "report/result_files.hpp"
#include "report/svg_chart.hpp"
#include "scene/j232_setup.hpp"
#include "random/stream.hpp"
#include "scenario/scenario.hpp"
#include "scenario/scenario_reader.hpp"

using namespace j232;

namespace {
std::string scenario_path(const char* name) { return std::string(J232_SOURCE_DIR) + "/scenarios/" + name; }
}  // namespace

TEST_CASE("board: mark classification table", "[board]") {
  scenario::BoardSpec b;  // 110 J/m, hits at 0.3 of the puncture energy
  const double L = 0.0508, D = 0.00251;
  const double crush = b.crush_depth;
  const double point_first = board::presented_width(L, D, 1.0, crush), broadside = board::presented_width(L, D, 0.0, crush);
  CHECK(point_first == Approx(D));
  CHECK(broadside == Approx(L));
  // Nearly flat, the whole shank is within the crush depth; steeper, only its part that is.
  CHECK(board::presented_width(L, D, 0.1, crush) == Approx(L * std::sqrt(0.99) + D * 0.1));
  CHECK(board::presented_width(L, D, std::cos(1.0), crush) == Approx(crush / std::cos(1.0) * std::sin(1.0) + D * std::cos(1.0)));
  CHECK(board::presented_width(L, D, std::cos(1.0), 1.0) == Approx(L * std::sin(1.0) + D * std::cos(1.0)));  // a deep crush: the whole nail
  struct Row {
    double energy, width;
    board::Mark expected;
  };
  const Row table[] = {
      {0.05, point_first, board::Mark::None},  {0.09, point_first, board::Mark::Hit},    {0.28, point_first, board::Mark::Puncture},
      {1.0, broadside, board::Mark::None},     {1.7, broadside, board::Mark::Hit},       {5.5, broadside, board::Mark::Hit},
      {5.6, broadside, board::Mark::Puncture}, {10.0, broadside, board::Mark::Puncture},
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
  // The bound at no successes is exactly 0, not 1e-19 (which a report would print).
  for (std::uint64_t n : {1u, 7u, 2000u, 123457u}) {
    CHECK(assess::wilson(0, n).low == 0.0);
    CHECK(assess::wilson(n, n).high == 1.0);
  }
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

namespace {
// A run with its marks.csv collected through the runner's sink, as `j232 run` writes it.
struct Collected {
  assess::Assessment a;
  std::string marks = report::marks_csv_header();
};
Collected run_collecting(const assess::Simulator& sim, int threads) {
  Collected c;
  c.a = assess::run_assessment(sim, threads, nullptr, [&](const assess::MarkRow& row) { report::append_marks_csv_row(c.marks, row, sim); });
  return c;
}
}  // namespace

TEST_CASE("determinism: the same result, bit for bit, on 1 and 2 threads and in any grouping", "[assess][determinism][long]") {
  // Chain guards (random passes) on a deck whose skirt is raised above the blade, so that
  // many nails get out and mark the board: every random draw of the pipeline is exercised.
  auto s = scenario::read_scenario(scenario_path("highway-pivoted-chains.toml"));
  s.housing.skirt_bottom = 0.09;
  for (auto& g : s.housing.guards) g.openness = 0.5;
  s.run.replicates = 48;
  const assess::Simulator sim(s);
  const auto one = run_collecting(sim, 1);
  const auto two = run_collecting(sim, 2);
  const report::Provenance p{"test", "test", "today", "digest", 0, 0, {}, 1};
  const auto sum_one = assess::summarise(one.a, s), sum_two = assess::summarise(two.a, s);
  const auto json_one = report::result_json(s, one.a, sum_one, p), json_two = report::result_json(s, two.a, sum_two, p);
  CHECK(json_one.dump() == json_two.dump());
  CHECK(one.marks == two.marks);
  CHECK(one.marks.size() > 1000);
  const auto soup = scene::build_scene_soup(s);
  const auto pictures_one = report::pictures_json(s, one.a, soup), pictures_two = report::pictures_json(s, two.a, soup);
  CHECK(pictures_one.dump() == pictures_two.dump());
  auto page_one = json_one, page_two = json_two;
  page_one["pictures"] = pictures_one, page_two["pictures"] = pictures_two;
  CHECK(report::compliance_report_html(report::as_saved(page_one)) == report::compliance_report_html(report::as_saved(page_two)));
  // Replicates run in two pieces merge to the same result as one run.
  assess::Assessment parts;
  std::string part_marks = report::marks_csv_header();
  const assess::MarkSink sink = [&](const assess::MarkRow& row) { report::append_marks_csv_row(part_marks, row, sim); };
  assess::run_replicates(sim, 0, 24, parts, nullptr, sink);
  assess::run_replicates(sim, 24, 24, parts, nullptr, sink);
  CHECK(report::result_json(s, parts, assess::summarise(parts, s), p).dump() == json_one.dump());
  CHECK(part_marks == one.marks);
  // Another seed gives another result.
  s.run.seed += 1;
  const assess::Simulator other(s);
  CHECK(run_collecting(other, 2).marks != one.marks);
}

TEST_CASE("memory: nothing is kept per replicate; share quantiles are exact from their counts", "[assess][memory][long]") {
  // The share distribution gives the same quantiles as sorting every replicate's share.
  std::vector<double> all;
  assess::ShareDistribution d;
  random::Stream rng(7, 0, 0, random::Purpose::Feed);
  for (int r = 0; r < 1001; ++r) {
    const double share = std::floor(rng.uniform() * 12) / 150.0;
    all.push_back(share);
    d.add(share);
  }
  std::sort(all.begin(), all.end());
  for (double p : {0.0, 0.05, 0.33, 0.5, 0.95, 1.0}) CHECK(d.quantile(p) == assess::quantile_sorted(all, p));
  CHECK(d.counts.size() <= 12);

  // A run many times longer keeps the same amount: the mark sample stays bounded.
  auto s = scenario::read_scenario(scenario_path("highway-pivoted-raised-skirt.toml"));
  s.feed.nails = 30;
  s.run.replicates = 3000;
  const assess::Simulator sim(s);
  std::uint64_t streamed = 0;
  const auto a = assess::run_assessment(sim, 2, nullptr, [&](const assess::MarkRow&) { ++streamed; });
  CHECK(a.replicates == 3000);
  CHECK(streamed == a.marks + a.uncounted_marks - a.unlocated_marks);
  CHECK(streamed > assess::kMarkSample);
  CHECK(a.mark_sample.size() <= assess::kMarkSample);
  CHECK(a.mark_sample_replicates < 3000);
  CHECK(a.shares[0].counts.size() <= 31);
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

TEST_CASE("stop rule: batches run until the verdict's interval is narrow enough", "[assess][stop][long]") {
  auto s = scenario::read_scenario(scenario_path("highway-pivoted-raised-skirt.toml"));
  s.run.replicates = 16;
  s.run.target_half_width = 0.02;
  s.run.max_replicates = 400;
  s.run.estimator = scenario::RunSpec::Estimator::Replicates;
  const assess::Simulator sim(s);
  const auto a = assess::run_assessment(sim, 2);
  const auto sum = assess::summarise(a, s, assess::kExactDraws);
  // Batches grow by half the replicates so far (at least the first batch's 16).
  std::vector<std::uint64_t> sizes{16};
  while (sizes.back() < 400) sizes.push_back(std::min<std::uint64_t>(400, sizes.back() + std::max<std::uint64_t>(16, sizes.back() / 2)));
  CHECK(std::find(sizes.begin(), sizes.end(), a.replicates) != sizes.end());
  CHECK(a.replicates > 16);  // one batch of 16 cannot reach +/- 0.02
  CHECK(a.looks == static_cast<int>(std::find(sizes.begin(), sizes.end(), a.replicates) - sizes.begin()) + 1);
  const bool narrow = 0.5 * (sum.verdict.pass.high - sum.verdict.pass.low) <= 0.02;
  CHECK(a.stopped_by == (narrow ? "target_half_width" : "max_replicates"));
  CHECK(sum.verdict.basis == assess::Basis::Replicates);
  // ...and it stopped at the first batch that was narrow enough.
  const auto at = std::find(sizes.begin(), sizes.end(), a.replicates);
  assess::Assessment shorter;
  assess::run_replicates(sim, 0, *(at - 1), shorter, nullptr);
  const auto before = assess::summarise(shorter, s, assess::kExactDraws);
  CHECK(0.5 * (before.verdict.pass.high - before.verdict.pass.low) > 0.02);
}

TEST_CASE("stop rule: until settled, the exact estimate settles a verdict with fewer replicates than the replicates' share", "[assess][stop][long]") {
  auto s = scenario::read_scenario(scenario_path("highway-pivoted.toml"));
  s.run.replicates = 20;
  s.run.until_settled = true;
  s.run.max_replicates = 2000;
  const auto settle = [&](scenario::RunSpec::Estimator e) {
    s.run.estimator = e;
    const auto a = assess::run_assessment(assess::Simulator(s), 2);
    const auto sum = assess::summarise(a, s, assess::kExactDraws);
    // The interval the report shows is the one that stopped the run.
    CHECK(a.stopped_by == "settled");
    CHECK(sum.settled);
    CHECK(sum.passes);
    return a.replicates;
  };
  const auto exact = settle(scenario::RunSpec::Estimator::EveryNail);
  const auto replicates = settle(scenario::RunSpec::Estimator::Replicates);
  INFO("settled after " << exact << " replicates from every nail, " << replicates << " from the replicates' share");
  CHECK(exact < replicates);
  // A verdict that cannot settle within max_replicates says so.
  s.run.max_replicates = 20;
  s.run.estimator = scenario::RunSpec::Estimator::Replicates;
  const auto a = assess::run_assessment(assess::Simulator(s), 2);
  CHECK(a.replicates == 20);
  CHECK(a.stopped_by == "max_replicates");
}

TEST_CASE("re-strikes: in a closed deck some nails come back into the blade's disc and are struck again", "[assess][restrike][long]") {
  auto s = scenario::read_scenario(scenario_path("highway-pivoted.toml"));
  s.run.replicates = 200;
  const assess::Simulator sim(s);
  const auto a = assess::run_assessment(sim, 2);
  CHECK(a.strikes.total == a.struck);
  CHECK(a.strikes.mean() > 1.0);          // strikes per struck nail, the first included
  CHECK(a.strikes.counts[1] < a.struck);  // some struck more than once
  CHECK(a.strikes.counts[0] == 0);        // every struck nail was struck at least once
  const auto sum = assess::summarise(a, s);
  CHECK(sum.validity.valid);
}

TEST_CASE("similarity: thrown speed follows blade speed when the feed scales with it", "[assess][similarity][long]") {
  // Every speed of the strike scaled by k (the blade's, the nail's fall and drift) leaves
  // the geometry of each contact the same: the thrown speed must scale by k and the launch
  // elevation stay (gravity and drag barely act within a pass). At a fixed feed instead the
  // blade meets the falling nail k times more often, nearer its tip, and throws it slower
  // for its speed (docs/validation.md §3): the depth a nail falls between two passes,
  // against its length, is the similarity number that report 445-1's central impact lacks.
  auto slow = scenario::read_scenario(scenario_path("highway-pivoted.toml"));
  slow.run.replicates = 100;
  const double k = 3;
  auto fast = slow, fast_same_feed = slow;
  for (auto* s : {&fast, &fast_same_feed})
    for (auto& sp : s->spindles) sp.blade.omega *= k;
  fast.feed.drop_height *= k * k;
  fast.feed.outlet_speed_max *= k;
  fast.feed.ground_speed *= k;
  const auto a_slow = assess::run_assessment(assess::Simulator(slow), 2);
  const auto a_fast = assess::run_assessment(assess::Simulator(fast), 2);
  const auto a_same = assess::run_assessment(assess::Simulator(fast_same_feed), 2);
  const double struck_slow = static_cast<double>(a_slow.struck) / static_cast<double>(a_slow.nails);
  const double struck_fast = static_cast<double>(a_fast.struck) / static_cast<double>(a_fast.nails);
  INFO("struck " << struck_slow << " and " << struck_fast << "; thrown speed " << a_slow.exit_speed.mean() << ", "
                 << a_fast.exit_speed.mean() << " and at the same feed " << a_same.exit_speed.mean() << " m/s; elevation "
                 << a_slow.launch_elevation.mean() << ", " << a_fast.launch_elevation.mean() << " and " << a_same.launch_elevation.mean()
                 << " deg");
  // Gravity is not scaled: it speeds the slow nail's fall through the blade by some 10 %,
  // so a few more of the slow nails fall past between two passes.
  CHECK(std::abs(struck_fast - struck_slow) < 0.05);
  CHECK(a_fast.exit_speed.mean() / a_slow.exit_speed.mean() == Approx(k).epsilon(0.03));
  CHECK(a_fast.exit_speed.quantile(0.95) / a_slow.exit_speed.quantile(0.95) == Approx(k).epsilon(0.03));  // the histogram reaches that far
  CHECK(std::abs(a_fast.launch_elevation.mean() - a_slow.launch_elevation.mean()) < 2.0);
  // The same blade speed with the test's own feed: nearer the tip, slower, steeper.
  CHECK(a_same.exit_speed.mean() / a_slow.exit_speed.mean() < 0.93 * k);
  CHECK(a_same.launch_elevation.mean() > a_slow.launch_elevation.mean() + 10.0);
}

TEST_CASE("trace: the way out is the last crossing of the deck's outline; the first is kept", "[assess][trace][long]") {
  // Chains hang across the openings: a nail that slips under the deck's edge and is turned
  // back by the chains or the turf, then leaves elsewhere, is named by where it finally left.
  auto s = scenario::read_scenario(scenario_path("highway-pivoted-chains.toml"));
  const assess::Simulator sim(s);
  int differ = 0, came_back = 0, marked = 0;
  for (std::uint64_t r = 0; r < 20; ++r)
    for (int n = 0; n < s.feed.nails; ++n) {
      const auto o = sim.simulate(r, n);
      const auto& t = o.flight.trace;
      if (t.exit != flight::Exit::Inside) CHECK(t.first_exit != flight::Exit::Inside);  // it left, so it first left
      if (o.flight.mark_count > 0) {
        ++marked;
        CHECK(t.exit != flight::Exit::Inside);  // a marking nail left for good
      }
      if (t.first_exit != flight::Exit::Inside && t.exit == flight::Exit::Inside) ++came_back;
      if (t.exit != flight::Exit::Inside && (t.first_exit != t.exit || t.first_exit_index != t.exit_index)) ++differ;
    }
  CHECK(marked > 10);
  CHECK(came_back + differ > 0);  // some nails crossed out and back
}

TEST_CASE("trace: every mark's trail is consistent and the ways out add up", "[assess][trace][long]") {
  // The deck with a side discharge: counted marks leave by the opening.
  auto deck = scenario::read_scenario(scenario_path("deck-72in-three-spindle.toml"));
  deck.run.replicates = 40;
  const assess::Simulator sim(deck);
  std::vector<assess::MarkRow> rows;
  const auto a = assess::run_assessment(sim, 2, nullptr, [&](const assess::MarkRow& r) { rows.push_back(r); });
  REQUIRE(rows.size() > 100);
  for (const auto& r : rows) {
    const auto& t = r.trace;
    REQUIRE(t.touch_count > 0);
    if (t.touch_count <= flight::NailTrace::kMaxTouches) {
      CHECK(t.touches[static_cast<std::size_t>(t.touch_count - 1)] == flight::Touch::Board);  // a mark ends at the board
      int blade = 0;
      for (int i = 0; i < t.touch_count; ++i) blade += t.touches[static_cast<std::size_t>(i)] == flight::Touch::Blade;
      CHECK(r.strikes == 1 + blade);  // the first strike is not listed
    }
    CHECK(t.exit != flight::Exit::Inside);  // the board stands outside the deck
    CHECK(t.last_strike_speed > 0);
    CHECK(r.flight_time > 0);
    CHECK(r.spindle < 3);
  }
  std::uint64_t by_exit = 0, by_strikes = 0, by_first = 0, nails = 0;
  for (const auto& [key, row] : a.exits.marks)
    for (auto n : row) by_exit += n;
  for (auto n : a.exits.marks_by_strikes) by_strikes += n;
  for (auto n : a.exits.marks_by_first_touch) by_first += n;
  for (const auto& [key, n] : a.exits.nails) nails += n;
  CHECK(by_exit == a.marks);  // every counted mark has a way out
  CHECK(by_strikes == a.marks);
  CHECK(by_first == a.marks);
  CHECK(nails == a.struck);
  const auto opening = a.exits.marks.find(assess::exit_key(flight::Exit::Opening, 0));
  REQUIRE(opening != a.exits.marks.end());
  std::uint64_t through = 0;
  for (auto n : opening->second) through += n;
  // Both ways out carry marks: the opening, and under the skirt (the nails the blade's faces
  // send down past the skirt's foot and off the turf: docs/validation.md).
  CHECK(through > 0);
  const auto under = a.exits.marks.find(assess::exit_key(flight::Exit::UnderSkirt, 0));
  REQUIRE(under != a.exits.marks.end());
  CHECK(a.exit_names.at(assess::exit_key(flight::Exit::Opening, 0)) == "opening: side discharge");
  CHECK(a.exit_names.at(assess::exit_key(flight::Exit::UnderSkirt, 0)) == "under the skirt");

  // A chained deck with its skirt raised: nails leave through the chains, and are named so.
  auto chains = scenario::read_scenario(scenario_path("highway-pivoted-chains.toml"));
  chains.housing.skirt_bottom = 0.09;
  for (auto& g : chains.housing.guards) g.openness = 0.5;
  chains.run.replicates = 40;
  const assess::Simulator chained(chains);
  const auto c = assess::run_assessment(chained, 2);
  bool through_guard = false;
  for (const auto& [key, n] : c.exits.nails)
    if (assess::exit_of(key) == flight::Exit::Guard && n > 0) {
      through_guard = true;
      const auto& name = c.exit_names.at(key);
      CHECK((name == "guard: front chains" || name == "guard: rear chains"));
    }
  CHECK(through_guard);
}

TEST_CASE("trajectories: a traced nail does what it did in the run, and notable nails are capped", "[assess][trajectories]") {
  auto s = scenario::read_scenario(scenario_path("highway-pivoted-chains.toml"));
  s.housing.skirt_bottom = 0.09;
  for (auto& g : s.housing.guards) g.openness = 0.5;
  s.run.replicates = 8;
  const assess::Simulator sim(s);
  std::vector<assess::MarkRow> rows;
  assess::run_assessment(sim, 2, nullptr, [&](const assess::MarkRow& r) { rows.push_back(r); });
  REQUIRE(rows.size() > 20);
  std::vector<flight::Vec3> path;
  for (std::size_t i = 0; i < rows.size(); i += 7) {
    const auto& row = rows[i];
    const auto plain = sim.simulate(row.replicate, static_cast<int>(row.nail));
    const auto traced = sim.trace(row.replicate, static_cast<int>(row.nail), path);
    // Recording the path changes nothing about the nail.
    CHECK(traced.flight.fate == plain.flight.fate);
    CHECK(traced.flight.strikes == row.strikes);
    CHECK(traced.flight.mark_count == plain.flight.mark_count);
    CHECK(traced.flight.end_position == plain.flight.end_position);
    CHECK(traced.flight.flight_time == row.flight_time);
    REQUIRE(path.size() >= 2);
    // The path ends where the nail ended, passes within half a nail of its mark (the mark is
    // where the nail's surface touched the board, its centre on the path), and never jumps
    // further than the nail can fly in one chord.
    CHECK((path.back() - plain.flight.end_position).norm() < 1e-9);
    double nearest = HUGE_VAL;
    for (std::size_t k = 1; k < path.size(); ++k) {
      const flight::Vec3 d = path[k] - path[k - 1];
      const double t = d.squaredNorm() > 0 ? std::clamp((row.mark.point - path[k - 1]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      nearest = std::min(nearest, (path[k - 1] + t * d - row.mark.point).norm());
    }
    CHECK(nearest <= 0.5 * (s.nail.length + s.nail.length_tolerance) + 1e-9);
    for (std::size_t k = 1; k < path.size(); ++k) CHECK((path[k] - path[k - 1]).norm() < 2.0);
  }
  // Notable nails: counted marks in the zone or punctures, each nail once, up to the cap of
  // each kind, chosen the same whatever the order of the nails.
  auto row = [](std::uint32_t replicate, std::uint32_t nail, bool counted, bool zone, bool puncture) {
    assess::MarkRow r;
    r.replicate = replicate, r.nail = nail;
    r.mark.counted = counted, r.mark.in_zone = zone, r.mark.puncture = puncture;
    return r;
  };
  assess::NotableNails notable(5), reversed(5);
  for (std::uint32_t n = 0; n < 8; ++n) {
    notable.add(row(0, n, true, true, false));
    notable.add(row(0, n, true, true, true));  // a second mark of the same nail is the same nail
  }
  for (std::uint32_t n = 8; n-- > 0;) reversed.add(row(0, n, true, true, false));
  reversed.add(row(1, 97, true, true, false));
  notable.add(row(1, 99, false, true, true));   // below the blade plane: not notable
  notable.add(row(1, 98, true, false, false));  // a hit outside the zone: not notable
  notable.add(row(1, 97, true, false, true));   // a puncture outside the zone, then a zone mark:
  notable.add(row(1, 97, true, true, false));   // drawn as a zone nail
  notable.add(row(1, 96, true, false, true));
  CHECK(notable.zone().size() == 5);
  CHECK(notable.zone() == reversed.zone());
  CHECK(notable.puncture() == std::vector<assess::NotableNails::NailId>{{1, 96}});
  CHECK(notable.seen() == 10);
  CHECK(notable.not_kept() == 4);
  const auto traced = assess::trace_nails(sim, 3, notable);
  REQUIRE(traced.size() == 9);
  for (int i = 0; i < 3; ++i) CHECK(traced[static_cast<std::size_t>(i)].why == "sample");
  CHECK(traced.back().why == "puncture");
  for (const auto& t : traced) CHECK(t.points.size() >= 2);
}

TEST_CASE("spinning nails: air.spin_average = false is read and follows the axis in short steps", "[assess][drag]") {
  const std::string path = std::string(J232_BINARY_DIR) + "/spin-reference.toml";
  {
    std::ifstream in(scenario_path("highway-pivoted.toml"));
    std::ofstream out(path);
    out << in.rdbuf() << "\n[air]\nspin_average = false\n";
  }
  const auto reference = scenario::read_scenario(path);
  CHECK_FALSE(reference.air.spin_average);
  const auto averaged = scenario::read_scenario(scenario_path("highway-pivoted.toml"));
  CHECK(averaged.air.spin_average);
  const assess::Simulator ref_sim(reference), avg_sim(averaged);
  long long ref_queries = 0, avg_queries = 0;
  int struck = 0;
  for (int nail = 0; nail < 40; ++nail) {
    const auto r = ref_sim.simulate(0, nail), a = avg_sim.simulate(0, nail);
    CHECK(r.contact_radius == a.contact_radius);  // the first strike is the same
    if (r.flight.fate == flight::Fate::NotStruck) continue;
    ++struck;
    ref_queries += r.flight.queries, avg_queries += a.flight.queries;
  }
  REQUIRE(struck > 10);
  // The axis turns tens of radians within an averaged chord. (A query is now one broad-phase
  // gather per chord or slide, the same for both; 5047 against 1218 when written: 4.1x.)
  CHECK(ref_queries > 3 * avg_queries);
}

TEST_CASE("replay: a replayed nail is the nail of the run, and its events add up to its outcome", "[assess][trajectories]") {
  auto s = scenario::read_scenario(scenario_path("highway-pivoted-chains.toml"));
  s.run.replicates = 3;
  const assess::Simulator sim(s);
  int marked = 0, restruck = 0, passed = 0;
  for (std::uint64_t r = 0; r < 3; ++r)
    for (int n = 0; n < s.feed.nails; ++n) {
      const auto plain = sim.simulate(r, n);
      const auto replay = sim.replay(r, n);
      const auto& f = replay.outcome.flight;
      // Recording changes nothing.
      CHECK(f.fate == plain.flight.fate);
      CHECK(f.end_position == plain.flight.end_position);
      CHECK(f.mark_count == plain.flight.mark_count);
      // (A nail cut off may have been cut off at its strike, before any flight, or in flight.)
      if (plain.flight.fate != flight::Fate::CutOff) CHECK(replay.struck == (plain.flight.fate != flight::Fate::NotStruck));
      if (!replay.struck) continue;
      // The events: every bounce and later strike, one end with the fate, a board event
      // with the board's own energy, times that never go back.
      int bounces = 0, gentle = 0, strikes = 1, boards = 0, passes = 0;
      double t = replay.strike.time;
      for (const auto& e : replay.events) {
        CHECK(e.time >= t);
        t = e.time;
        bounces += e.kind == flight::FlightEvent::Kind::Bounce && !e.gentle;
        gentle += e.kind == flight::FlightEvent::Kind::Bounce && e.gentle;
        strikes += e.kind == flight::FlightEvent::Kind::Strike;
        passes += e.kind == flight::FlightEvent::Kind::GuardPass;
        if (e.kind == flight::FlightEvent::Kind::Board) {
          if (boards++ == 0) CHECK(e.energy == f.board_energy);
          CHECK((e.mark > 0) == (f.mark_count > 0));
        }
      }
      REQUIRE(!replay.events.empty());
      CHECK(replay.events.back().kind == flight::FlightEvent::Kind::End);
      CHECK(replay.events.back().fate == f.fate);
      CHECK(bounces == f.bounces);
      CHECK(gentle == f.gentle_contacts);
      CHECK(strikes == f.strikes);
      CHECK(boards == (f.board_energy >= 0 ? 1 : 0));
      marked += f.mark_count > 0, restruck += f.strikes > 1, passed += passes > 0;
    }
  CHECK(marked > 5);
  CHECK(restruck > 5);
  CHECK(passed > 5);
}

namespace {
// A toy feed: every nail of station s makes outcome k with probability probs[s][k].
struct ToyFeed {
  std::vector<assess::OutcomeDistribution> stations;
  // Draws one nail of station s.
  assess::NailMarks draw(std::size_t s, random::Stream& rng) const {
    double u = rng.uniform();
    for (const auto& [o, p] : stations[s]) {
      if (u < p) return o;
      u -= p;
    }
    return stations[s].back().first;
  }
};
std::uint32_t key_of(const assess::NailMarks& m) {
  flight::FlightResult f;
  f.hits_zone = m[0], f.punctures_zone = m[1], f.hits_outside = m[2], f.punctures_outside = m[3];
  return assess::marks_key(f);
}
}  // namespace

TEST_CASE("exact P(pass): the dynamic programme against enumeration and simulation", "[statistics]") {
  // Two stations, 6 nails (3 each), outcomes with up to two marks, small limits: every
  // combination of the nails' outcomes enumerated (4^6).
  const ToyFeed toy{{{{{0, 0, 0, 0}, 0.6}, {{1, 0, 0, 0}, 0.2}, {{0, 0, 1, 0}, 0.15}, {{0, 1, 1, 0}, 0.05}},
                     {{{0, 0, 0, 0}, 0.7}, {{0, 0, 0, 1}, 0.1}, {{0, 0, 2, 0}, 0.1}, {{1, 0, 0, 1}, 0.1}}}};
  const std::array<int, assess::kCategories> allowed{1, 0, 2, 1};
  double enumerated = 0;
  for (int code = 0; code < 4096; ++code) {
    double p = 1;
    std::array<int, assess::kCategories> sum{};
    for (int i = 0; i < 6; ++i) {
      const auto& [o, q] = toy.stations[static_cast<std::size_t>(i % 2)][static_cast<std::size_t>(code >> (2 * i) & 3)];
      p *= q;
      for (int c = 0; c < assess::kCategories; ++c) sum[static_cast<std::size_t>(c)] += o[static_cast<std::size_t>(c)];
    }
    bool pass = true;
    for (int c = 0; c < assess::kCategories; ++c) pass = pass && sum[static_cast<std::size_t>(c)] <= allowed[static_cast<std::size_t>(c)];
    if (pass) enumerated += p;
  }
  CHECK(assess::pass_probability(toy.stations, 6, allowed) == Approx(enumerated).epsilon(1e-12));
  // The allowed counts follow the replicate judgement's rule (30 of 150 passes 20 %).
  scenario::CriteriaSpec j232;
  CHECK(assess::allowed_count(j232, assess::HitsZone, 150) == 30);
  CHECK(assess::allowed_count(j232, assess::PuncturesZone, 150) == 0);
  CHECK(assess::allowed_count(j232, assess::HitsOutside, 150) == 22);
  CHECK(assess::allowed_count(j232, assess::PuncturesOutside, 150) == 7);
  // 150 nails at J232's limits against 40 000 simulated tests.
  const ToyFeed feed{{{{{0, 0, 0, 0}, 0.87}, {{0, 0, 1, 0}, 0.08}, {{0, 0, 0, 1}, 0.045}, {{1, 0, 0, 0}, 0.005}},
                      {{{0, 0, 0, 0}, 0.9}, {{0, 0, 1, 0}, 0.06}, {{0, 0, 0, 1}, 0.039}, {{0, 1, 0, 0}, 0.001}}}};
  std::array<int, assess::kCategories> limits{};
  for (int c = 0; c < assess::kCategories; ++c) limits[static_cast<std::size_t>(c)] = assess::allowed_count(j232, c, 150);
  const double exact = assess::pass_probability(feed.stations, 150, limits);
  random::Stream rng(5, 0, 0, random::Purpose::Test);
  int passed = 0;
  const int tests = 40000;
  for (int t = 0; t < tests; ++t) {
    std::array<int, assess::kCategories> sum{};
    for (int i = 0; i < 150; ++i) {
      const auto o = feed.draw(static_cast<std::size_t>(i % 2), rng);
      for (int c = 0; c < assess::kCategories; ++c) sum[static_cast<std::size_t>(c)] += o[static_cast<std::size_t>(c)];
    }
    bool pass = true;
    for (int c = 0; c < assess::kCategories; ++c) pass = pass && sum[static_cast<std::size_t>(c)] <= limits[static_cast<std::size_t>(c)];
    passed += pass;
  }
  const double share = static_cast<double>(passed) / tests;
  INFO("exact " << exact << ", simulated " << share);
  CHECK(exact > 0.1);
  CHECK(exact < 0.9);
  CHECK(std::abs(share - exact) < 4 * std::sqrt(exact * (1 - exact) / tests));
}

TEST_CASE("exact P(pass): its interval covers the truth about 95 % of the time", "[statistics][long]") {
  // A small test (40 nails, two stations) with known per-nail probabilities: 300 runs of
  // 150 replicates each, the interval from 200 bootstrap draws.
  const ToyFeed feed{{{{{0, 0, 0, 0}, 0.86}, {{0, 0, 1, 0}, 0.09}, {{0, 0, 0, 1}, 0.04}, {{1, 0, 0, 0}, 0.01}},
                      {{{0, 0, 0, 0}, 0.9}, {{0, 0, 1, 0}, 0.07}, {{0, 0, 0, 1}, 0.028}, {{0, 1, 0, 0}, 0.002}}}};
  scenario::CriteriaSpec j232;
  const int nails = 40;
  std::array<int, assess::kCategories> limits{};
  for (int c = 0; c < assess::kCategories; ++c) limits[static_cast<std::size_t>(c)] = assess::allowed_count(j232, c, nails);
  const double truth = assess::pass_probability(feed.stations, nails, limits);
  int covered = 0, runs = 300;
  double width = 0;
  for (int run = 0; run < runs; ++run) {
    random::Stream rng(11, static_cast<std::uint64_t>(run), 0, random::Purpose::Test);
    assess::StationOutcomes seen;
    for (int r = 0; r < 150; ++r)
      for (int i = 0; i < nails; ++i) seen.add(i % 2, key_of(feed.draw(static_cast<std::size_t>(i % 2), rng)));
    const auto e = assess::exact_pass(seen, nails, j232, static_cast<std::uint64_t>(run), 200);
    REQUIRE(e.computed);
    covered += e.low <= truth && truth <= e.high;
    width += e.high - e.low;
  }
  const double coverage = static_cast<double>(covered) / runs;
  INFO("truth " << truth << ", coverage " << coverage << ", mean width " << width / runs);
  CHECK(truth > 0.2);
  CHECK(truth < 0.95);
  CHECK(coverage > 0.90);
  CHECK(coverage <= 1.0);
  // Not computed where it cannot be, with the reason.
  scenario::CriteriaSpec by_marks;
  by_marks.denominator = scenario::CriteriaSpec::Denominator::Marks;
  assess::StationOutcomes one;
  one.add(0, 0);
  const auto e = assess::exact_pass(one, 1, by_marks, 1, 10);
  CHECK_FALSE(e.computed);
  CHECK_THAT(e.not_computed, Catch::Contains("marks"));
}

TEST_CASE("exact P(pass): agrees with the replicates' estimate on a mower near neither end", "[assess][statistics][long]") {
  auto s = scenario::read_scenario(scenario_path("deck-72in-three-spindle.toml"));
  s.run.replicates = 200;
  s.run.target_half_width.reset();
  const auto a = assess::run_assessment(assess::Simulator(s), 2);
  const auto sum = assess::summarise(a, s, 200);
  REQUIRE(sum.exact.computed);
  INFO("replicates " << sum.pass.estimate << " (" << sum.pass.low << "-" << sum.pass.high << "), exact " << sum.exact.value << " ("
                     << sum.exact.low << "-" << sum.exact.high << ")");
  CHECK(sum.pass.estimate > 0.05);
  CHECK(sum.pass.estimate < 0.95);
  CHECK(sum.exact.value >= sum.pass.low);
  CHECK(sum.exact.value <= sum.pass.high);
  CHECK(sum.pass.estimate >= sum.exact.low - 0.02);
  CHECK(sum.pass.estimate <= sum.exact.high + 0.02);
  CHECK(sum.exact.high - sum.exact.low < sum.pass.high - sum.pass.low);  // every nail tells more than every test
}

TEST_CASE("warnings: a cut-off share nearing the invalidity limit names the limits that cut nails off", "[assess]") {
  const auto s = scenario::read_scenario(scenario_path("highway-pivoted.toml"));
  const auto with_cut_offs = [&](std::uint64_t by_time, std::uint64_t by_bounces) {
    assess::Assessment a;
    a.replicates = 10, a.nails = 1500, a.struck = 1000;
    a.fates[static_cast<std::size_t>(flight::Fate::CutOff)] = by_time + by_bounces;
    for (std::uint64_t i = 0; i < by_time; ++i) a.cut_off_by.add(static_cast<double>(flight::CutOff::TimeLimit));
    for (std::uint64_t i = 0; i < by_bounces; ++i) a.cut_off_by.add(static_cast<double>(flight::CutOff::MaxBounces));
    return assess::summarise(a, s);
  };
  const auto mentions = [](const std::vector<std::string>& lines, const std::string& what) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(what) != std::string::npos; });
  };
  // 0.2 %: nothing said.
  const auto quiet = with_cut_offs(1, 1);
  CHECK(quiet.validity.valid);
  CHECK_FALSE(mentions(quiet.warnings, "cut off"));
  // 0.5 %: warned, naming both limits with their values, the commoner first.
  const auto near = with_cut_offs(2, 3);
  CHECK(near.validity.valid);
  REQUIRE(mentions(near.warnings, "cut off"));
  CHECK(mentions(near.warnings, "3 by [run] max_bounces (400), 2 by [run] time_limit (3 s)"));
  CHECK(near.cut_off_by[static_cast<std::size_t>(flight::CutOff::MaxBounces)] == 3);
  // 1.5 %: invalid, and the reason names them too.
  const auto invalid = with_cut_offs(15, 0);
  CHECK_FALSE(invalid.validity.valid);
  CHECK(mentions(invalid.validity.reasons, "15 by [run] time_limit (3 s)"));
  CHECK_FALSE(mentions(invalid.warnings, "cut off"));
}

TEST_CASE("warnings: a blade faster than 100 m/s at the tip is called unusual, not refused", "[assess]") {
  auto s = scenario::read_scenario(scenario_path("highway-pivoted.toml"));
  for (auto& sp : s.spindles) sp.blade.omega *= 2.0;  // 63.8 -> 127.6 m/s
  assess::Assessment a;
  a.replicates = 1, a.nails = 150, a.struck = 100;
  const auto sum = assess::summarise(a, s);
  CHECK(sum.validity.valid);
  REQUIRE(sum.warnings.size() == 1);
  CHECK(sum.warnings[0].find("unusual") != std::string::npos);
}

TEST_CASE("result files: JSON numbers are written without binary noise, and rewriting changes nothing", "[report]") {
  nlohmann::ordered_json j;
  j["thirty"] = 0.1 * 300;              // 30.000000000000004 in binary arithmetic
  j["sum"] = 0.1 + 0.2;                 // 0.30000000000000004
  j["tiny"] = 3e-76 * (1 + 1e-15);      // a relative change far below 1e-12 goes, the scale stays
  j["list"] = {1.0 / 3.0, 29.999999999999996, -2.5e-300};
  j["count"] = 1234567890123456789ULL;  // integers are not rounded
  j["text"] = "0.30000000000000004";    // nor strings
  const std::string text = report::json_text(j, -1);
  CHECK(text ==
        R"({"thirty":30.0,"sum":0.3,"tiny":3e-76,"list":[0.333333333333,30.0,-2.5e-300],"count":1234567890123456789,"text":"0.30000000000000004"})");
  // Read back and written again: the same text.
  CHECK(report::json_text(nlohmann::ordered_json::parse(text), -1) == text);
  // nlohmann's Grisu2 writes the double nearest 0.182594302 as 0.18259430200000001 (a wall
  // time that once failed the CLI's noise check): no number may come out longer than 12
  // significant digits, over a spread of values like the timings a run records.
  const auto longest = [](const std::string& number) {
    std::string digits;
    for (const char c : number.substr(0, number.find_first_of("eE")))
      if (c >= '0' && c <= '9') digits += c;
    digits.erase(0, digits.find_first_not_of('0'));
    digits.erase(digits.find_last_not_of('0') + 1);
    return digits.size();
  };
  CHECK(longest(report::json_text(nlohmann::json(0.182594302), -1)) <= 12);
  std::size_t worst = 0;
  for (int i = 1; i < 200000; ++i) {
    const double x = 1e-9 * static_cast<double>(i) * 1234567.891;  // 0.0012 ... 247 s
    worst = std::max(worst, longest(report::json_text(nlohmann::json(x), -1)));
  }
  CHECK(worst <= 12);
}

TEST_CASE("report pages: a name's control characters (NUL, ESC) never reach a page raw", "[report]") {
  const std::string hostile = std::string("lane\x1b[31m<b>red") + '\0' + "\x7f" + "end\ttab";
  const std::string shown = report::escape(hostile);
  CHECK(shown.find('\x1b') == std::string::npos);
  CHECK(shown.find('\0') == std::string::npos);
  CHECK(shown.find('\x7f') == std::string::npos);
  CHECK(shown == "lane\xEF\xBF\xBD[31m&lt;b&gt;red\xEF\xBF\xBD\xEF\xBF\xBD" "end\ttab");
}

TEST_CASE("charts: a logarithmic axis has a tick at each power of ten and draws zero on its floor", "[report]") {
  report::Chart c("t", "x", "y", 640, 360);
  c.y_log_range(1e-6, 1);
  c.points({0.0, 1.0, 2.0}, {0.0, 1e-6, 1.0}, "#000000", "", 2.0, false);  // (open circles: one element each)
  const std::string svg = c.svg();
  // The ticks: 10⁻⁶ ... 10⁻¹, 1.
  for (const char* label : {">10⁻⁶<", ">10⁻³<", ">10⁻¹<", ">1<"}) CHECK(svg.find(label) != std::string::npos);
  CHECK(svg.find(">10⁻⁷<") == std::string::npos);
  // Zero and the floor at one height, the top far above them.
  const auto heights = [&] {
    std::vector<double> y;
    for (std::size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) {
      const std::size_t cy = svg.find("cy=\"", at);
      y.push_back(std::stod(svg.substr(cy + 4)));
    }
    return y;
  }();
  REQUIRE(heights.size() == 3);
  CHECK(heights[0] == heights[1]);
  CHECK(heights[2] < heights[1] - 100);
  report::Chart bad("t", "x", "y");
  bad.y_log_range(0, 1);
  CHECK_THROWS(bad.svg());
}
