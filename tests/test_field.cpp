// The mower at work in a field (j232 hazard): the [field] form and its refusals, the
// strata and their reach shares, the tally's geometry against analytic densities, ballistic
// flights against the range formula and an accurate drag solution, the intervals' coverage,
// and thread-count determinism.
#include <catch2/catch.hpp>
#include <boost/math/distributions/normal.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <vector>
#include <string>
#include <toml++/toml.h>

#include "assess/simulator.hpp"
#include "field/field_compare.hpp"
#include "field/field_simulator.hpp"
#include "field/hazard_run.hpp"
#include "field/hazard_tally.hpp"
#include "flight/nail_flight.hpp"
#include "random/stream.hpp"
#include "report/hazard_report.hpp"
#include "report/html_table.hpp"
#include "report/result_files.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario_reader.hpp"
#include "units/quantity.hpp"
#include "field_scenario.hpp"

using namespace j232;

namespace {
using test::kMower;
using test::kStones;

scenario::Scenario read(const std::string& text) {
  return scenario::read_scenario(toml::parse(text, std::string_view("field.toml")), "field.toml");
}

std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const scenario::InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("field: the [field] form, with its defaults", "[field][input]") {
  const auto s = read(kMower + kStones);
  REQUIRE(s.field.present);
  REQUIRE(s.field.objects.size() == 1);
  const auto& o = s.field.objects[0];
  CHECK(o.median_size == Approx(0.030));
  CHECK(o.per_area == Approx(0.5));
  CHECK(o.density == Approx(2650));
  CHECK(o.restitution.value() == Approx(0.5));
  CHECK(s.field.planes.at(0).receptor == scenario::FieldPlaneSpec::Receptor::Vehicle);
  CHECK(s.field.ground_speed == Approx(8 / 3.6));
  CHECK_FALSE(s.run.time_limit);  // not written: derived
  CHECK(s.time_limit() == Approx(20.0));  // a field's flights last seconds
  // A stone trapped in a chained deck rattles for seconds before it leaves: ten times a
  // nail's bounces; strikes: one whole push along a knife (max_contacts_per_pass) and 5 000
  // besides (a nail: 500); a written limit is kept.
  CHECK(s.max_bounces() == 4000);
  CHECK(s.max_strikes() == 20000 + 5000);
  CHECK(read(kMower).max_bounces() == 400);
  CHECK(read(kMower).max_strikes() == 20000 + 500);
  CHECK(read(kMower + "[run]\nmax_contacts_per_pass = 300\n").max_strikes() == 300 + 500);
  CHECK(read(kMower + "[run]\nmax_bounces = 50\nmax_strikes = 60\n" + kStones).max_bounces() == 50);
  CHECK(read(kMower + "[run]\nmax_bounces = 50\nmax_strikes = 60\n" + kStones).max_strikes() == 60);
  CHECK(s.field.person_energy == Approx(79));
  CHECK(s.field.acceptable_area == Approx(55.74));
  CHECK(!o.rolls);  // a stone skids unless the scenario calls it round
  CHECK(s.ground.rolling_resistance == Approx(0.3));
  std::string round = kMower + "[ground]\nrolling_resistance = 0.2\n" + kStones;
  round.replace(round.find("embedment = 0.2"), 15, "embedment = 0.2\nrolls = true");
  const auto r = read(round);
  CHECK(r.field.objects[0].rolls);
  CHECK(r.ground.rolling_resistance == Approx(0.2));
  // A J232 test's nails do not roll: the key is refused there, naming it.
  CHECK_THAT(error_of(kMower + "[ground]\nrolling_resistance = 0.2\n"), Catch::Contains("ground.rolling_resistance") && Catch::Contains("field scenario"));
  CHECK_THAT(error_of(kMower + "[ground]\nrolling_resistance = 3\n" + kStones), Catch::Contains("ground.rolling_resistance") && Catch::Contains("3"));
  std::string bad = kMower + kStones;
  bad.replace(bad.find("embedment = 0.2"), 15, "embedment = 0.2\nrolls = \"yes\"");
  CHECK_THAT(error_of(bad), Catch::Contains("rolls"));
}

TEST_CASE("field: stones that roll go farther than stones that skid, over the same objects", "[field][ground]") {
  auto s = read(kMower + kStones);
  s.field.objects_simulated = 1500;
  // On the mower's steel friction spins a stone up, and one that skids leaves without that
  // spin: with frictionless steel none is given, and the two fly alike until they are down
  // (but for the knife's spin, which a skidding stone leaves on the steel).
  s.housing.friction = 0;
  for (auto& g : s.housing.guards) g.friction = 0;
  const field::FieldSimulator skid_sim(s);
  const auto skid_run = field::run_hazard(skid_sim, 2);
  const auto skid = field::summarise(skid_sim, skid_run);
  s.field.objects[0].rolls = true;
  const field::FieldSimulator roll_sim(s);
  const auto roll_run = field::run_hazard(roll_sim, 2);
  const auto roll = field::summarise(roll_sim, roll_run);
  // The same objects are struck the same way (the strike does not know how they end, nor
  // does frictionless steel), and rolling adds distance once they are down: the objects
  // whose farthest contact lies beyond 10 m grow.
  CHECK(roll.thrown_per_km == skid.thrown_per_km);
  // (Not each object: a ball landing with the backspin a knife gave it screws back once its
  // slip closes, where a skidding stone, whose spin the turf takes, slides on. The farthest
  // of all is one object and may be either.)
  const auto beyond = [](const field::HazardRun& r, double d) {
    std::uint64_t n = 0;
    for (const auto& t : r.strata)
      for (std::size_t i = static_cast<std::size_t>(d / 0.25); i < t.farthest.size(); ++i) n += t.farthest[i];
    return n;
  };
  INFO("beyond 10 m: skidding " << beyond(skid_run, 10) << ", rolling " << beyond(roll_run, 10) << "; beyond 3 m " << beyond(skid_run, 3) << ", " << beyond(roll_run, 3) << "; beyond 30 m " << beyond(skid_run, 30) << ", " << beyond(roll_run, 30));
  CHECK(beyond(roll_run, 10) > beyond(skid_run, 10) + 20);
}

TEST_CASE("field: a steel ball is one size of steel, struck with the scenario's restitution", "[field][input]") {
  const auto s = read(kMower + "[restitution]\ne = 0.8\n" + R"(
[field]
support_height = "0 mm"
[[field.objects]]
kind = "steel_ball"
median_size = "60 mm"
per_area = "0.1 m^-2"
)");
  const auto& o = s.field.objects.at(0);
  CHECK(o.kind == scenario::FieldObjectSpec::Kind::SteelBall);
  CHECK(o.density == Approx(7850));
  CHECK(o.spread == 1.0);
  CHECK(o.min_size == Approx(0.060));
  CHECK(o.max_size == Approx(0.060));
  CHECK_FALSE(o.restitution.has_value());  // the scenario's [restitution]
  CHECK(o.drag_coefficient == Approx(0.47));
  const field::FieldSimulator sim(s);
  CHECK(sim.reach_share(0) == 1.0);  // lying on the turf, 60 mm tall: above the blade's lower face (2 in - 3 mm)
  // 8 mm: it stands 8 mm tall, and nothing lifts it.
  CHECK_THROWS_AS(read(kMower + "[field]\nsupport_height = \"0 mm\"\n[[field.objects]]\nkind = \"steel_ball\"\nmedian_size = \"8 mm\"\nper_area = \"1 m^-2\"\n"),
                  scenario::InputError);
}

TEST_CASE("field: bad fields are refused with the key and what was expected", "[field][input]") {
  CHECK_THAT(error_of(kMower + "[field]\n"), Catch::Contains("field.objects") && Catch::Contains("without objects"));
  // Too tall to pass under the deck's front.
  std::string tall = kStones;
  tall.replace(tall.find("max_size = \"70 mm\""), 18, "max_size = \"150 mm\"");
  CHECK_THAT(error_of(kMower + tall), Catch::Contains("max_size") && Catch::Contains("cannot pass under"));
  // Too small to reach the blade, and nothing lifts them.
  std::string small = kStones;
  small.replace(small.find("max_size = \"70 mm\""), 18, "max_size = \"30 mm\"");
  small.replace(small.find("min_size = \"10 mm\""), 18, "min_size = \"5 mm\"");
  CHECK_THAT(error_of(kMower + small), Catch::Contains("no object stands up to the blade"));
  // A plane inside the deck, and one beyond the range.
  std::string inside = kStones;
  inside.replace(inside.find("distance = \"4 m\""), 16, "distance = \"0.2 m\"");
  CHECK_THAT(error_of(kMower + inside), Catch::Contains("distance") && Catch::Contains("inside the mower's deck"));
  std::string beyond = kStones;
  beyond.replace(beyond.find("distance = \"4 m\""), 16, "distance = \"400 m\"");
  CHECK_THAT(error_of(kMower + beyond), Catch::Contains("within field.range"));
  CHECK_THAT(error_of(kMower + kStones + "[[field.objects]]\nmedian_size = \"20 mm\"\n"), Catch::Contains("per_area") && Catch::Contains("missing"));
  CHECK_THAT(error_of(kMower + kStones + "[[field.objects]]\nmedian_size = \"20 mm\"\nper_area = \"-1 m^-2\"\n"), Catch::Contains("per_area"));
  CHECK_THAT(error_of(kMower + kStones + "[[field.objects]]\nmedian_size = \"20 mm\"\nper_area = \"1 m^-2\"\ncolour = \"grey\"\n"),
             Catch::Contains("colour"));
  // The J232 rig has no meaning in a field, nor the field in a J232 run.
  CHECK_THAT(error_of(kMower + "[board]\nhit_fraction = 0.3\n" + kStones), Catch::Contains("[board]") && Catch::Contains("no J232 test rig"));
  CHECK_THAT(error_of(kMower + kStones + "[run]\nreplicates = 100\n"), Catch::Contains("replicates"));
  CHECK_THROWS_AS(assess::Simulator(read(kMower + kStones)), scenario::InputError);
  CHECK_THROWS_AS(field::FieldSimulator(read(kMower)), scenario::InputError);
}

namespace {
// The stones of kStones held up by supports of mean `mean` (m), under a blade `inches` up,
// its deck's skirt 1 in above it (the whole deck set to the cut, as a mower's wheels set it).
std::string supported_stones(double mean, double inches = 2) {
  std::string mower = kMower, stones = kStones;
  mower.replace(mower.find("height = \"2 in\""), 15, fmt::format("height = \"{} in\"", inches));
  mower.replace(mower.find("skirt_bottom = \"3 in\""), std::string("skirt_bottom = \"3 in\"").size(), fmt::format("skirt_bottom = \"{} in\"", inches + 1));
  stones.replace(stones.find("support_height = \"0 mm\""), 23, fmt::format("support_height = \"{} mm\"", 1e3 * mean));
  return mower + stones;
}

// Kolmogorov's statistic of values that should be uniform on [0, 1].
double ks_uniform(std::vector<double> u) {
  std::sort(u.begin(), u.end());
  double d = 0;
  const double n = static_cast<double>(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) {
    const double k = static_cast<double>(i);
    d = std::max({d, (k + 1) / n - u[i], u[i] - k / n});
  }
  return d;
}
}  // namespace

TEST_CASE("field: what holds a stone up: the share that reaches and the draws, against an independent quadrature", "[field]") {
  // kStones (lognormal 30 mm, spread 1.6, 10-70 mm, sunk 20 %) under the 2-in blade (its
  // lower face 3 mm lower), the skirt's foot 3 in up: a stone of size d reaches when its
  // support b puts its top b + 0.8 d between the face and the foot. b is exponential (or
  // half-normal) of mean 12 mm. The share, the size's distribution and the support's, worked
  // out here by direct quadrature over d (not by the simulator's grid and envelope).
  const double mean = 0.012, face = 2 * units::inch - 0.003, foot = 3 * units::inch;
  for (const bool half_normal : {false, true}) {
    INFO((half_normal ? "half-normal" : "exponential") << " supports");
    std::string text = supported_stones(mean);
    if (half_normal) text.replace(text.find("support_height"), 0, "support_shape = \"half_normal\"\n");
    const auto s = read(text);
    REQUIRE((s.field.support_shape == scenario::FieldSpec::SupportShape::HalfNormal) == half_normal);
    const field::FieldSimulator sim(s);
    // P(b > x): exp(-x / mean), or for the half-normal of that mean (sigma = mean sqrt(pi/2))
    // 2 (1 - Phi(x / sigma)), from Boost's normal distribution (not the erfc the code uses).
    const boost::math::normal_distribution<double> z;
    const double sigma = mean * std::sqrt(units::pi / 2);
    const auto tail = [&](double x) { return half_normal ? 2 * boost::math::cdf(boost::math::complement(z, x / sigma)) : std::exp(-x / mean); };
    const auto band_of = [&](double d) { return std::array<double, 2>{std::max(0.0, face - 0.8 * d), foot - 0.8 * d}; };
    const auto reach = [&](double d) {
      const auto b = band_of(d);
      return b[1] > b[0] ? tail(b[0]) - tail(b[1]) : 0.0;
    };
    const double sl = std::log(1.6);
    const auto pdf = [&](double d) { return boost::math::pdf(z, std::log(d / 0.030) / sl) / (d * sl); };
    const double whole = boost::math::cdf(z, std::log(0.070 / 0.030) / sl) - boost::math::cdf(z, std::log(0.010 / 0.030) / sl);
    constexpr int kSteps = 200000;
    std::vector<double> cumulative(kSteps + 1, 0.0);
    for (int i = 0; i < kSteps; ++i) {
      const double d = 0.010 + (0.060 * (i + 0.5)) / kSteps;  // midpoint rule
      cumulative[static_cast<std::size_t>(i) + 1] = cumulative[static_cast<std::size_t>(i)] + pdf(d) * reach(d) * 0.060 / kSteps;
    }
    CHECK(sim.reach_share(0) == Approx(cumulative.back() / whole).epsilon(1e-6));
    // The old model (every stone on the plane) reaches fewer: only those taller than the face.
    CHECK(sim.reach_share(0) > field::FieldSimulator(read(kMower + kStones)).reach_share(0));

    // The size strata: each one's share is the quadrature's between its sizes, and they
    // cover the reachable sizes without gap or overlap.
    const auto cumulative_at = [&](double d) {  // the quadrature's cumulative at size d
      const double x = std::clamp((d - 0.010) / 0.060 * kSteps, 0.0, static_cast<double>(kSteps));
      const auto i = std::min(static_cast<std::size_t>(x), static_cast<std::size_t>(kSteps) - 1);
      return cumulative[i] + (x - static_cast<double>(i)) * (cumulative[i + 1] - cumulative[i]);
    };
    REQUIRE(sim.strata() == field::FieldSimulator::kSizeStrata);
    for (std::size_t k = 0; k < sim.strata(); ++k) {
      const auto& st = sim.stratum(k);
      INFO("stratum " << k << ": " << st.smallest << " to " << st.largest << " m");
      CHECK(st.share == Approx((cumulative_at(st.largest) - cumulative_at(st.smallest)) / whole).epsilon(1e-3));
      if (k > 0) CHECK(st.smallest == sim.stratum(k - 1).largest);
    }
    CHECK(sim.stratum(0).smallest == Approx(0.010));
    CHECK(sim.stratum(sim.strata() - 1).largest <= 0.070);
    // Each drawn stone's size (within its stratum, object i of stratum i mod S) and support,
    // through their distribution functions (probability integral transform): uniform if the
    // draws follow the distributions above.
    std::vector<double> u_size, u_support;
    for (std::uint64_t i = 0; i < 3000; ++i) {
      const auto e = sim.simulate(i).encounter;
      const auto& st = sim.stratum(i % sim.strata());
      const double d = e.body.diameter;
      REQUIRE_FALSE(e.lifted);  // no updraft
      REQUIRE(d >= st.smallest);
      REQUIRE(d <= st.largest);
      const auto b = band_of(d);
      REQUIRE(e.support >= b[0] - 1e-12);
      REQUIRE(e.support <= b[1] + 1e-12);
      CHECK(e.height == Approx(e.support + 0.5 * d - 0.2 * d));
      u_size.push_back((cumulative_at(d) - cumulative_at(st.smallest)) / (cumulative_at(st.largest) - cumulative_at(st.smallest)));
      u_support.push_back((tail(b[0]) - tail(e.support)) / (tail(b[0]) - tail(b[1])));
    }
    // Kolmogorov's 1 % critical value 1.63 / sqrt(n), and a grid of 60 um: 0.03 at n = 3000.
    CHECK(ks_uniform(u_size) < 1.63 / std::sqrt(3000.0));
    CHECK(ks_uniform(u_support) < 1.63 / std::sqrt(3000.0));
  }
  // A shape with no supports to shape is refused, naming the key.
  std::string none = kMower + kStones;
  none.replace(none.find("support_height"), 0, "support_shape = \"half_normal\"\n");
  CHECK_THAT(error_of(none), Catch::Contains("field.support_shape") && Catch::Contains("support_height above 0"));
  std::string odd = supported_stones(mean);
  odd.replace(odd.find("support_height"), 0, "support_shape = \"uniform\"\n");
  CHECK_THAT(error_of(odd), Catch::Contains("field.support_shape") && Catch::Contains("uniform"));
}

TEST_CASE("field: with supports, the share that reaches falls smoothly with the cut, and small stones are not refused", "[field]") {
  // Every 1/4 in from 2 to 6 in: falling, never by more than 3x a step (the old model's step
  // from all to none is what a support's spread removes).
  double last = 1;
  for (int quarter = 8; quarter <= 24; ++quarter) {
    const auto s = read(supported_stones(0.010, quarter / 4.0));
    const double share = field::FieldSimulator(s).reach_share(0);
    INFO(quarter / 4.0 << " in: " << share);
    CHECK(share > 0);
    CHECK(share < last);
    if (quarter > 8) CHECK(last / share < 3);
    last = share;
  }
  // The stones too small to stand up to the blade on the plane (refused without support).
  std::string small = supported_stones(0.010);
  small.replace(small.find("max_size = \"70 mm\""), 18, "max_size = \"30 mm\"");
  small.replace(small.find("min_size = \"10 mm\""), 18, "min_size = \"5 mm\"");
  const field::FieldSimulator sim(read(small));
  CHECK(sim.reach_share(0) > 0);
  CHECK(sim.reach_share(0) < 0.2);
  // Stones taller than the deck's front gap: with supports, left to the model (pushed aside)
  // and said; without, refused (the test above).
  std::string tall = supported_stones(0.010);
  tall.replace(tall.find("max_size = \"70 mm\""), 18, "max_size = \"150 mm\"");
  const auto s = read(tall);
  CAPTURE(s.notes);
  CHECK(std::count_if(s.notes.begin(), s.notes.end(), [](const std::string& n) { return n.find("pushed aside") != std::string::npos; }) == 1);
  // The blade hangs below the skirt's foot (2 in against 3 in): said in a field's words.
  CHECK(std::count_if(s.notes.begin(), s.notes.end(), [](const std::string& n) { return n.find("objects it sends down") != std::string::npos; }) == 1);
  const field::FieldSimulator with_tall(s);
  for (std::uint64_t i = 0; i < 200; ++i) {  // every stone drawn stands below the front gap (the skirt's foot, 3 in up)
    const auto e = with_tall.simulate(i).encounter;
    CHECK(e.support + 0.8 * e.body.diameter < 3 * units::inch + 1e-12);
  }
  CHECK(with_tall.reach_share(0) > 0);
}

TEST_CASE("field: each kind drawn among the sizes that can reach a blade", "[field]") {
  const auto s = read(kMower + kStones);
  const field::FieldSimulator sim(s);
  // Stones stand up to the blade's lower face (2 in - 3 mm) when (1 - 0.2) d exceeds it.
  const double face = 2 * units::inch - 0.003, tall = face / 0.8;
  const boost::math::normal_distribution<double> z;
  auto F = [&](double d) { return boost::math::cdf(z, std::log(d / 0.030) / std::log(1.6)); };
  const double expected = (F(0.070) - F(tall)) / (F(0.070) - F(0.010));
  CHECK(sim.reach_share(0) == Approx(expected).epsilon(1e-9));
  // Met across the cut widened by half the largest size each side.
  CHECK(sim.objects_per_metre(0) == Approx(0.5 * (2 * s.spindles[0].blade.tip_radius() + 0.070)));
  bool struck_outside_tip_circle = false;
  for (std::uint64_t i = 0; i < 2000 && !struck_outside_tip_circle; ++i) {
    const auto o = sim.simulate(i);
    struck_outside_tip_circle |= std::abs(o.encounter.lateral) > s.spindles[0].blade.tip_radius() && o.fate != field::ObjectFate::NotReached;
  }
  CHECK(struck_outside_tip_circle);  // a blade reaches a stone whose centre lies just outside its tip circle
  // Every object drawn is of a size that can reach.
  for (std::uint64_t i = 0; i < 300; ++i) {
    const auto o = sim.simulate(i);
    CHECK(o.encounter.body.diameter >= tall - 1e-12);
    CHECK(o.encounter.body.diameter <= 0.070 + 1e-12);
  }
}

TEST_CASE("field: the updraft lifts the sizes whose drag exceeds their weight", "[field]") {
  std::string lifted = kStones;
  lifted.replace(lifted.find("[field]\n"), 8, "[field]\nupdraft_speed = \"25 m/s\"\n");
  const auto s = read(kMower + lifted);
  const field::FieldSimulator sim(s);
  const double below = 3 * 1.2 * 0.6 * 25 * 25 / (4 * 2650 * units::standard_gravity);
  bool any_lifted = false;
  for (std::uint64_t i = 0; i < 400; ++i) {
    const auto e = sim.simulate(i).encounter;
    CHECK(e.lifted == (e.body.diameter < below));
    any_lifted |= e.lifted;
  }
  CHECK(any_lifted);
}

TEST_CASE("field: the combined interval covers a known rate 95 % of the time", "[field][stats]") {
  // Two strata with known per-object Poisson rates (objects that strike several times too).
  const double rate_a = 0.004, rate_b = 0.05, w_a = 3.0, w_b = 0.2;
  const std::uint64_t n_a = 4000, n_b = 2000;
  const double truth = w_a * rate_a + w_b * rate_b;
  int covered = 0;
  const int trials = 1000;
  for (int t = 0; t < trials; ++t) {
    random::Stream rng(7, static_cast<std::uint64_t>(t), 0, random::Purpose::Test);
    auto poisson = [&](double mean) {
      int k = 0;
      for (double p = std::exp(-mean), u = rng.uniform(), c = p; u > c; ++k) p *= mean / (k + 1), c += p;
      return static_cast<std::uint64_t>(k);
    };
    field::CountSum a, b;
    for (std::uint64_t i = 0; i < n_a; ++i) a.add(poisson(rate_a));
    for (std::uint64_t i = 0; i < n_b; ++i) b.add(poisson(rate_b));
    const auto e = field::combined({{a, w_a / n_a}, {b, w_b / n_b}});
    covered += e.low <= truth && truth <= e.high;
  }
  const double coverage = static_cast<double>(covered) / trials;
  CHECK(coverage >= 0.93);
  CHECK(coverage <= 0.985);
  // A heavy stratum that expects less than one event beside a light one that sees many: the
  // upper end still covers it (Fay and Feuer's interval adds one event of the heaviest weight).
  {
    int heavy_covered = 0;
    const double light_rate = 0.2, heavy_rate = 0.0002, w_light = 0.01, w_heavy = 5.0;
    const std::uint64_t n_light = 3000, n_heavy = 3000;
    const double heavy_truth = w_light * light_rate + w_heavy * heavy_rate;
    for (int t = 0; t < trials; ++t) {
      random::Stream rng(9, static_cast<std::uint64_t>(t), 0, random::Purpose::Test);
      field::CountSum light, heavy;
      for (std::uint64_t i = 0; i < n_light; ++i) light.add(rng.uniform() < light_rate ? 1 : 0);
      for (std::uint64_t i = 0; i < n_heavy; ++i) heavy.add(rng.uniform() < heavy_rate ? 1 : 0);
      const auto e = field::combined({{light, w_light / n_light}, {heavy, w_heavy / n_heavy}});
      heavy_covered += e.low <= heavy_truth && heavy_truth <= e.high;
    }
    CHECK(static_cast<double>(heavy_covered) / trials >= 0.93);
  }
  // Nothing seen: Garwood's upper end, -ln 0.025 per object of the heaviest stratum.
  const auto none = field::combined({{field::CountSum{}, 2.0 / 1000}, {field::CountSum{}, 1.0 / 1000}});
  CHECK(none.value == 0);
  CHECK(none.high == Approx(-std::log(0.025) * 2.0 / 1000));
  // The heaviest weight one more event could carry: a stratum that cannot make the event
  // does not count, unless it made it.
  field::CountSum seen;
  seen.add(1);
  CHECK(field::heaviest_weight({{field::CountSum{}, 9.0, false}, {seen, 5.0, false}, {field::CountSum{}, 3.0, true}}) == 5.0);
  CHECK(field::heaviest_weight({{field::CountSum{}, 9.0, false}, {field::CountSum{}, 3.0, true}}) == 3.0);
  CHECK(field::heaviest_weight({{field::CountSum{}, 9.0, false}}) == 0.0);
}

TEST_CASE("field: the tally's strips against an analytic density falling as 1/R^2", "[field][stats]") {
  // Objects come down at a distance R from the mower uniformly in azimuth with density
  // 1 / (R ln(Rmax/Rmin)) on [Rmin, Rmax]: per m^2, 1 / (2 pi R^2 ln(Rmax/Rmin)). A strip at
  // lateral distance d >= Rmin then holds atan(sqrt(Rmax^2 - d^2) / d) / (pi d L) per metre
  // of its width (L = ln(Rmax/Rmin)).
  const double r_min = 2, r_max = 60, L = std::log(r_max / r_min);
  field::HazardLayout layout;
  layout.range = 80, layout.cell = 1, layout.half_cells = 80, layout.person_energy = 1;
  field::HazardTally tally(layout);
  field::ObjectWatch watch(tally);
  field::ObjectOutcome thrown;
  thrown.fate = field::ObjectFate::Thrown;
  thrown.flight.fate = flight::Fate::ShortOfBoard;
  const std::uint64_t n = 400000;
  random::Stream rng(11, 0, 0, random::Purpose::Test);
  for (std::uint64_t i = 0; i < n; ++i) {
    watch.thrown(1.0, 0.0);
    const double r = r_min * std::exp(rng.uniform() * L), a = units::two_pi * rng.uniform();
    watch.met_ground(0.0, {r * std::cos(a), r * std::sin(a), 0.0}, {0.0, 0.0, -10.0}, false);  // 50 J: hazardous
    watch.finish(thrown);
  }
  CHECK(tally.objects == n);
  std::uint64_t landed = 0;
  for (auto c : tally.landings) landed += c;
  CHECK(landed == n);
  for (int d : {4, 8, 16, 32}) {
    const double mid = d + 0.5;
    const double expected = std::atan(std::sqrt(r_max * r_max - mid * mid) / mid) / (units::pi * mid * L);  // per object, per metre
    for (int side : {0, 1}) {
      const auto e = field::combined({{tally.directions[static_cast<std::size_t>(side)][static_cast<std::size_t>(d)], 1.0 / static_cast<double>(n)}});
      INFO("d " << d << " side " << side << ": " << e.value << " (" << e.low << "-" << e.high << ") against " << expected);
      CHECK(e.low <= expected * 1.01);
      CHECK(e.high >= expected * 0.99);
    }
  }
}

namespace {
// A sphere flown from `from` at `velocity` over the field mower's turf (no blade in its way),
// its first ground contact outside the deck.
struct Landing {
  Eigen::Vector3d point, velocity;
  bool seen = false;
};
struct FirstGround final : flight::FlightObserver {
  Landing l;
  void flew(double, const Eigen::Vector3d&, const Eigen::Vector3d&, double, const Eigen::Vector3d&, const Eigen::Vector3d&) override {}
  void met_ground(double, const Eigen::Vector3d& point, const Eigen::Vector3d& v, bool in_deck) override {
    if (!l.seen && !in_deck) l = {point, v, true};
  }
};
Landing fly_sphere(const field::FieldSimulator& sim, const Eigen::Vector3d& from, const Eigen::Vector3d& velocity, double k) {
  const auto ball = projectile::Projectile::sphere(0.02, 2650 * units::pi * 0.02 * 0.02 * 0.02 / 6);
  flight::Body body;
  body.position = from, body.velocity = velocity, body.axis = Eigen::Vector3d::UnitZ(), body.spin = Eigen::Vector3d::Zero(), body.time = 0;
  flight::Drag drag;
  drag.on = k > 0, drag.k_axial = drag.k_normal = k, drag.sphere = true;
  flight::FlightContext context = sim.mower().context();
  FirstGround watch;
  context.observer = &watch;
  strike::BladePhases phases;
  random::EventDraws draws(1, 0, 0);
  flight::fly(body, ball, drag, context, phases, {}, draws);
  return watch.l;
}
}  // namespace

TEST_CASE("field: a launched object lands at the range formula without drag, at an accurate drag solution with it", "[field][flight]") {
  std::string smooth = kMower + "[ground]\nroughness = \"0 deg\"\n" + kStones;
  const field::FieldSimulator sim(read(smooth));
  const double g = units::standard_gravity, v = 30, angle = 25 * units::degree, r = 0.01, h0 = 1.0;
  const Eigen::Vector3d from(3.0, 0.0, h0), velocity(v * std::cos(angle), 0.0, v * std::sin(angle));
  // Without drag: the sphere touches the ground when its centre is r above it.
  const auto plain = fly_sphere(sim, from, velocity, 0.0);
  REQUIRE(plain.seen);
  const double vz = v * std::sin(angle), drop = h0 - r;
  const double range = v * std::cos(angle) * (vz + std::sqrt(vz * vz + 2 * g * drop)) / g;
  CHECK(plain.point.x() - from.x() == Approx(range).margin(0.01));
  CHECK(plain.point.z() == Approx(0).margin(1e-6));
  // With drag (k = rho Cd A / 2m): against RK4 at 10 us steps, to the same touch.
  const double k = 3 * 1.2 * 0.6 / (4 * 2650 * 0.02);
  const auto dragged = fly_sphere(sim, from, velocity, k);
  REQUIRE(dragged.seen);
  Eigen::Vector3d p = from, u = velocity;
  auto acc = [&](const Eigen::Vector3d& w) { return Eigen::Vector3d(-k * w.norm() * w + Eigen::Vector3d(0, 0, -g)); };
  const double dt = 1e-5;
  while (true) {
    const Eigen::Vector3d k1 = acc(u), k2 = acc(u + 0.5 * dt * k1), k3 = acc(u + 0.5 * dt * k2), k4 = acc(u + dt * k3);
    const Eigen::Vector3d p_next = p + dt * (u + dt / 6 * (k1 + k2 + k3));
    const Eigen::Vector3d u_next = u + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    if (p_next.z() <= r) {
      const double f = (p.z() - r) / (p.z() - p_next.z());
      p += f * (p_next - p), u += f * (u_next - u);
      break;
    }
    p = p_next, u = u_next;
  }
  INFO("drag range " << dragged.point.x() - from.x() << " against " << p.x() - from.x() << " (no drag " << range << ")");
  CHECK(p.x() - from.x() < 0.9 * range);  // drag matters here
  CHECK(dragged.point.x() == Approx(p.x()).margin(0.01));
  // The kinetic energy it arrives with, as the drag solution has it.
  CHECK(dragged.velocity.squaredNorm() == Approx(u.squaredNorm()).epsilon(0.005));
}

TEST_CASE("field: a hazard run is the same on 1 and 2 threads, and tallies what it met", "[field][determinism]") {
  auto s = read(kMower + kStones);
  s.field.objects_simulated = 2100;  // 9 chunks: on one thread in two waves, reusing its slots; on two in one
  const field::FieldSimulator sim(s);
  REQUIRE(field::slots_per_wave(field::HazardTally(field::HazardLayout::of(s.field)).bytes(), 1) < 9);
  REQUIRE(field::slots_per_wave(field::HazardTally(field::HazardLayout::of(s.field)).bytes(), 2) >= 9);
  const auto one = field::run_hazard(sim, 1), two = field::run_hazard(sim, 2);
  REQUIRE(one.strata.size() == field::FieldSimulator::kSizeStrata);  // one kind, in size strata
  const auto a = field::kind_tally(sim, one, 0), b = field::kind_tally(sim, two, 0);
  CHECK(a.objects == 2100);
  CHECK(a.fates == b.fates);
  CHECK(a.landings == b.landings);
  CHECK(a.hazardous == b.hazardous);
  CHECK(a.exit_speed == b.exit_speed);
  CHECK(a.max_distance == b.max_distance);
  for (std::size_t d = 0; d < 4; ++d)
    for (std::size_t k = 0; k < a.directions[d].size(); ++k) CHECK((a.directions[d][k].sum == b.directions[d][k].sum && a.directions[d][k].squares == b.directions[d][k].squares));
  CHECK(a.planes[0].by_height == b.planes[0].by_height);
  // Stones are thrown, fast, and few are cut off.
  const auto thrown = a.fates[static_cast<std::size_t>(field::ObjectFate::Thrown)];
  CHECK(thrown > 700);
  CHECK(a.fates[static_cast<std::size_t>(field::ObjectFate::CutOff)] < 21);
  const auto sum = field::summarise(sim, one);
  CHECK(sum.valid);
  // These stones stand only a little into the blade's plane: struck from above, pressed
  // into the soil, they skid away at a fraction of the tip's speed, never beyond it.
  CHECK(sum.exit_speed_q95 > 0.15 * s.tip_speed());
  CHECK(sum.exit_speed_q95 < 1.6 * s.tip_speed());
  CHECK(sum.max_distance > 10);
  CHECK(a.last_strike_speed == b.last_strike_speed);
  // A slot's tally cleared for its next chunk holds nothing of the last.
  field::HazardTally reused = a;
  reused.clear();
  CHECK(reused.pack() == field::HazardTally(a.layout).pack());
  CHECK(reused.pack() != a.pack());
}

TEST_CASE("field: the speed an object leaves with is its last blade strike's, in the ground's frame", "[field]") {
  const auto s = read(kMower + kStones);
  const field::FieldSimulator sim(s);
  const double v = s.field.ground_speed;
  int once = 0, again = 0, faster_again = 0;
  for (std::uint64_t i = 0; i < 600; ++i) {
    const auto o = sim.simulate(i);
    if (!field::counted_thrown(o.fate)) continue;
    // The last strike's velocity (the flight's frame) with the mower's travel added.
    const Eigen::Vector3d last = o.flight.trace.last_strike_velocity + Eigen::Vector3d(v, 0, 0);
    CHECK(o.last_strike_speed == Approx(last.norm()).margin(1e-12));
    CHECK(o.flight.trace.last_strike_speed == Approx(o.flight.trace.last_strike_velocity.norm()).margin(1e-12));
    if (o.flight.strikes == 1) {
      ++once;
      CHECK(o.last_strike_speed == Approx(o.exit_speed).margin(1e-9));  // struck once: the first strike is the last
    } else {
      ++again;
      faster_again += o.last_strike_speed > o.exit_speed;
    }
  }
  INFO(once << " struck once, " << again << " struck again (" << faster_again << " leaving faster than the first strike sent them)");
  CHECK(once > 0);
  CHECK(again > 0);
}

TEST_CASE("field: the knives meet an object sliding under the deck, as they meet one in flight", "[field]") {
  // A stone skidding along the turf under the deck, standing up into the blades' plane, is
  // struck by the next knife that sweeps it (before, a slide was searched against the deck's
  // faces only, and a skidding cobble passed under the knives untouched). Every strike that
  // ends a slide comes while the stone still slides: after the slide began, and with the stone
  // where the slide put it (on the turf).
  const auto s = read(kMower + kStones);
  const field::FieldSimulator sim(s);
  int slides = 0, struck_sliding = 0, struck_again_at_rest = 0;
  for (std::uint64_t i = 0; i < 400; ++i) {
    std::vector<flight::FlightEvent> events;
    sim.simulate(i, nullptr, &events);
    // A knife that nudged an object it could not move rides over it: it does not meet the
    // object, come to rest at that instant, again at that same instant.
    for (std::size_t k = 0, last = events.size(); k < events.size(); ++k) {
      if (events[k].kind != flight::FlightEvent::Kind::Strike) continue;
      if (last < k && events[last].time == events[k].time && events[last].spindle == events[k].spindle && events[last].edge == events[k].edge)
        for (std::size_t j = last + 1; j < k; ++j) struck_again_at_rest += events[j].kind == flight::FlightEvent::Kind::Rest;
      last = k;
    }
    for (std::size_t k = 0; k + 1 < events.size(); ++k) {
      if (events[k].kind != flight::FlightEvent::Kind::Slide) continue;
      ++slides;
      const auto& next = events[k + 1];
      if (next.kind != flight::FlightEvent::Kind::Strike) continue;
      ++struck_sliding;
      CHECK(next.time >= events[k].time);
      CHECK(next.centre.z() == Approx(events[k].centre.z()).margin(1e-9));  // still lying on the turf
    }
  }
  INFO(slides << " slides, " << struck_sliding << " ended by a knife");
  CHECK(struck_sliding > 0);
  CHECK(struck_again_at_rest == 0);
}

TEST_CASE("field: designs compared must count by the same energies and receptors", "[field][compare]") {
  auto base = scenario::read_scenario(std::string(J232_SOURCE_DIR) + "/scenarios/field/batwing-highway-shoulder.toml");
  base.field.objects_simulated = 16;
  auto stricter = base;
  stricter.field.person_energy = 40;
  CHECK_THROWS_WITH(field::compare_fields({base, stricter}, 1), Catch::Contains("field.person_energy") && Catch::Contains("same energies"));
  auto vehicle = base;
  vehicle.field.vehicle_energy = 3;
  CHECK_THROWS_WITH(field::compare_fields({base, vehicle}, 1), Catch::Contains("field.vehicle_energy"));
  REQUIRE(!base.field.planes.empty());
  auto other = base;
  auto& plane = other.field.planes.front();
  plane.receptor = plane.receptor == scenario::FieldPlaneSpec::Receptor::Person ? scenario::FieldPlaneSpec::Receptor::Vehicle
                                                                                : scenario::FieldPlaneSpec::Receptor::Person;
  CHECK_THROWS_WITH(field::compare_fields({base, other}, 1), Catch::Contains("another receptor"));
}

TEST_CASE("field: designs compared object by object, with common random numbers", "[field][compare][long]") {
  auto read_file = [](const char* name) { return scenario::read_scenario(std::string(J232_SOURCE_DIR) + "/scenarios/field/" + name); };
  auto without = read_file("batwing-highway-shoulder-no-chains.toml"), with = read_file("batwing-highway-shoulder.toml");
  without.field.objects_simulated = 3000;
  const auto c = field::compare_fields({without, with, without}, 2);
  REQUIRE(c.designs.size() == 3);
  REQUIRE(c.designs[1].differences.size() == c.designs[0].figures.size());
  // The chains stop nothing at the strike: the same objects thrown, none differing, and a
  // bound (not a zero-wide interval) on what the run could have missed.
  const auto& thrown = c.designs[1].differences[0];
  CHECK(thrown.objects_differing == 0);
  CHECK(thrown.per_km.value == 0);
  CHECK(thrown.per_km.low < 0);
  CHECK(thrown.per_km.high > 0);
  // They turn objects back: fewer first come down outside the deck, fewer cross the lane.
  CHECK(c.designs[1].differences[1].per_km.high < 0);
  CHECK(c.designs[1].differences[5].per_km.high < 0);  // the path on the left
  // A design against itself differs nowhere.
  for (const auto& d : c.designs[2].differences) CHECK(d.objects_differing == 0);
  // Paired: the difference's interval is narrower than the two designs' own intervals together.
  const auto& a = c.designs[0].figures[1].per_km;
  const auto& b = c.designs[1].figures[1].per_km;
  const auto& x = c.designs[1].differences[1].per_km;
  CHECK(x.high - x.low < (a.high - a.low) + (b.high - b.low));
  // The same on one thread; and run a chunk at a time (segments of 64 objects, rounded up to
  // whole chunks of 256), bit for bit: a long comparison holds one segment's counts.
  const auto one = field::compare_fields({without, with}, 1);
  for (std::size_t j = 0; j < one.designs[1].differences.size(); ++j) CHECK(one.designs[1].differences[j].per_km.value == c.designs[1].differences[j].per_km.value);
  std::uint64_t segments = 0;
  const auto pieces = field::compare_fields(
      {without, with}, 2, nullptr, [&](std::size_t d, const scenario::Scenario&, std::uint64_t, std::uint64_t, std::uint64_t) { segments += d == 0; }, 64);
  CHECK(segments == 12);  // 3000 objects in chunks of 256
  for (std::size_t d = 0; d < 2; ++d)
    for (std::size_t j = 0; j < one.designs[d].figures.size(); ++j) {
      CHECK(pieces.designs[d].figures[j].per_km.value == one.designs[d].figures[j].per_km.value);
      CHECK(pieces.designs[d].figures[j].per_km.low == one.designs[d].figures[j].per_km.low);
      CHECK(pieces.designs[d].figures[j].per_km.high == one.designs[d].figures[j].per_km.high);
      if (d == 1) {
        CHECK(pieces.designs[d].differences[j].per_km.low == one.designs[d].differences[j].per_km.low);
        CHECK(pieces.designs[d].differences[j].per_km.high == one.designs[d].differences[j].per_km.high);
        CHECK(pieces.designs[d].differences[j].objects_differing == one.designs[d].differences[j].objects_differing);
      }
    }
  for (std::size_t i = 0; i < one.designs[1].hazard.directions.size(); ++i)
    CHECK(pieces.designs[1].hazard.directions[i].hazard_distance == one.designs[1].hazard.directions[i].hazard_distance);
  // Each design's own hazard is what j232 hazard gives for it over the same objects.
  with.field.objects_simulated = without.field.objects_simulated;
  with.run.seed = without.run.seed;
  const field::FieldSimulator sim(with);
  const auto alone = field::summarise(sim, field::run_hazard(sim, 2));
  const auto& compared = c.designs[1].hazard;
  REQUIRE(compared.directions.size() == alone.directions.size());
  for (std::size_t i = 0; i < alone.directions.size(); ++i) {
    CHECK(compared.directions[i].hazard_distance == alone.directions[i].hazard_distance);
    CHECK(compared.directions[i].hazard_distance_upper == alone.directions[i].hazard_distance_upper);
    for (std::size_t k = 0; k < alone.directions[i].probability.size(); ++k)
      CHECK(compared.directions[i].probability[k].value == alone.directions[i].probability[k].value);
  }
  REQUIRE(compared.planes.size() == 2);
  // The comparison's own figure of each plane's hazardous crossings is j232 hazard's, its
  // interval included (one rule for the heaviest weight one more event could carry).
  for (std::size_t p = 0; p < 2; ++p) {
    const auto& figure = c.designs[1].figures[4 + 2 * p].per_km;
    const auto& own = alone.planes[p].hazardous_per_km;
    INFO("plane " << p);
    CHECK(figure.value == Approx(own.value).epsilon(1e-12));
    CHECK(figure.low == Approx(own.low).epsilon(1e-12));
    CHECK(figure.high == Approx(own.high).epsilon(1e-12));
  }
  CHECK(compared.planes[1].probability.value == alone.planes[1].probability.value);
  CHECK(compared.planes[1].probability.value > 0);
  CHECK(compared.planes[1].probability.value < c.designs[0].hazard.planes[1].probability.value);  // the chains protect the path
  const std::string text = report::hazard_comparison_text(c);
  CHECK_THAT(text, Catch::Contains("hazard distance (estimate / conservative): left") && Catch::Contains("P(struck) in one pass"));
  const auto j = report::hazard_comparison_json(c);
  const std::string html = report::hazard_comparison_html(j);
  CHECK_THAT(html, Catch::Contains("Each design's hazard") && Catch::Contains("Probability of being struck in one pass: left"));
  CHECK(j["designs"][1]["person_at_plane"][0]["plane"] == "path on the left");
  // The page is drawn from compare.json alone: the saved file (written and read back) draws
  // the same page.
  CHECK(report::hazard_comparison_html(nlohmann::ordered_json::parse(report::json_text(j))) == html);
  // In US units: every rate per mile (the figure's own, converted), the threshold in ft-lb.
  const report::DisplayUnits us{true};
  const std::string us_text = report::hazard_comparison_text(c, us), us_html = report::hazard_comparison_html(j, us);
  const auto& thrown_per_km = c.designs[1].figures[0].per_km;
  CHECK_THAT(us_text, Catch::Contains(fmt::format("{:.4g} per mile", 1.609344 * thrown_per_km.value)) && !Catch::Contains("per km") &&
                          !Catch::Contains(" J)") && Catch::Contains("ft-lb)"));
  CHECK_THAT(us_html, Catch::Contains("distance from the mower (ft)") && Catch::Contains("Figures per mile mowed") && !Catch::Contains("(m)"));
}

TEST_CASE("field: the strips' vertical planes count what an explicit plane at the same distance counts", "[field]") {
  std::string with_plane = kStones + "[[field.planes]]\nname = \"path\"\nside = \"left\"\ndistance = \"2.5 m\"\n";
  auto s = read(kMower + with_plane);
  s.field.objects_simulated = 3000;
  const field::FieldSimulator sim(s);
  const auto run = field::run_hazard(sim, 2);
  const auto t = field::kind_tally(sim, run, 0);
  // The strip plane at (2 + 1/2) cells on the left is the path's plane.
  CHECK(t.vertical[0][2].sum == t.planes[1].hazardous.sum);
  CHECK(t.vertical[0][2].squares == t.planes[1].hazardous.squares);
  CHECK(t.planes[1].hazardous.sum > 0);
  const auto sum = field::summarise(sim, run);
  // The curve starts beyond the deck: find 2.5 m on it.
  const auto& left = sum.directions[0];
  std::size_t at = 0;
  while (at < left.distance.size() && left.distance[at] != 2.5) ++at;
  REQUIRE(at < left.distance.size());
  CHECK(left.distance.front() >= left.deck_extent);
  CHECK(left.vertical[at].value == Approx(sum.planes[1].hazardous_per_area.value));
}

TEST_CASE("field: the hazard distance is the outer edge of the last cell at or above the acceptable density", "[field]") {
  auto s = read(kMower + kStones);
  const field::FieldSimulator sim(s);
  field::HazardRun run;
  // Every size stratum the same: n objects each, 900 of which strike 4 times each in every
  // strip on the left out to 10 m, more than the acceptable density (one per 55.74 m2);
  // nothing beyond, nothing elsewhere. Their weights add up to the kind's: w per object.
  const std::uint64_t n = 1000;
  const std::uint64_t count = 900 * 4;
  for (std::size_t j = 0; j < sim.strata(); ++j) {
    auto& t = run.strata.emplace_back(field::HazardLayout::of(s.field));
    t.objects = n;
    t.fates[static_cast<std::size_t>(field::ObjectFate::Thrown)] = n;
    for (std::size_t k = 0; k < 10; ++k) t.directions[0][k] = {count, 900 * 16};
  }
  const double w = sim.objects_per_metre(0) * sim.reach_share(0) / static_cast<double>(n);
  REQUIRE(w * static_cast<double>(count) > 1.5 / 55.74);
  const auto sum = field::summarise(sim, run);
  const auto& left = sum.directions[0];
  REQUIRE(!left.distance.empty());
  CHECK(left.distance.front() > left.deck_extent);  // the curve starts beyond the deck
  CHECK(left.hazard_distance == Approx(10.0));
  CHECK(left.hazard_distance_upper >= left.hazard_distance);
  CHECK_FALSE(left.beyond_range);
  // The right saw nothing: its hazard distance is the deck's edge.
  CHECK(sum.directions[1].hazard_distance == Approx(sum.directions[1].deck_extent));
  // The probability there: 1 - exp(-q A).
  CHECK(left.probability[3].value == Approx(-std::expm1(-left.exposure[3].value * 0.58)));
  CHECK(left.exposure[3].value == Approx(w * static_cast<double>(count)).epsilon(1e-12));
}

TEST_CASE("field: the setback at other acceptable densities, and a season's passes", "[field]") {
  std::string text = kMower + kStones + "[[field.planes]]\nname = \"path\"\nside = \"left\"\ndistance = \"2.5 m\"\n";
  text.replace(text.find("objects_simulated = 4000"), 24, "objects_simulated = 3000\npasses_per_season = 20\npeople_per_pass = 3");
  auto s = read(text);
  CHECK(s.field.passes_per_season == 20);
  CHECK(s.field.people_per_pass == 3);
  const field::FieldSimulator sim(s);
  const auto sum = field::summarise(sim, field::run_hazard(sim, 2));
  for (const auto& d : sum.directions) {
    REQUIRE(d.setbacks.size() == std::size(field::kSetbackFactors));
    CHECK(d.setbacks[2].acceptable_density == Approx(1 / s.field.acceptable_area));
    CHECK(d.setbacks[2].estimate == d.hazard_distance);  // the scenario's own
    CHECK(d.setbacks[2].conservative == d.hazard_distance_upper);
    for (std::size_t b = 0; b + 1 < d.setbacks.size(); ++b) {  // stricter: never nearer
      CHECK(d.setbacks[b].estimate >= d.setbacks[b + 1].estimate);
      CHECK(d.setbacks[b].conservative >= d.setbacks[b + 1].conservative);
      CHECK(d.setbacks[b].conservative >= d.setbacks[b].estimate);
    }
  }
  const auto& path = sum.planes.at(1);
  REQUIRE(path.probability.value > 0);
  CHECK(path.probability_per_season.value == Approx(1 - std::pow(1 - path.probability.value, 20)).epsilon(1e-12));
  CHECK(path.probability_per_season.high == Approx(1 - std::pow(1 - path.probability.high, 20)).epsilon(1e-12));
  CHECK(path.people_struck_per_season.value == Approx(60 * path.probability.value));
  CHECK(path.probability_per_season.value > path.probability.value);
  CHECK(path.probability_per_season.value < 20 * path.probability.value);
  std::string none = kMower + kStones;
  none.replace(none.find("objects_simulated = 4000"), 24, "objects_simulated = 4000\npasses_per_season = 0");
  CHECK_THAT(error_of(none), Catch::Contains("field.passes_per_season") && Catch::Contains("0"));
}

TEST_CASE("field: --units us shows the same figures in ft, mph, ft-lb and per mile; the JSON keeps SI", "[field][units]") {
  const report::DisplayUnits us = report::display_units("us"), si = report::display_units("si");
  CHECK(us.length(0.3048) == Approx(1.0).epsilon(1e-15));
  CHECK(us.per_mowed(1.0) == Approx(1.609344).epsilon(1e-15));     // per km -> per mile
  CHECK(us.energy(79.0) == Approx(58.267).epsilon(1e-4));           // DDESB's 79 J is its 58 ft-lb
  CHECK(us.area(55.74) == Approx(600.0).epsilon(1e-3));             // and its 55.7 m2, 600 ft2
  CHECK(us.speed(44.704) == Approx(100.0).epsilon(1e-12));          // mph
  CHECK(us.travel(8 / 3.6) == Approx(4.97).epsilon(1e-3));
  CHECK(si.length(3.0) == 3.0);
  CHECK(si.per_area(2.0) == 2.0);
  CHECK(us.per_area(1.0) == Approx(0.09290304).epsilon(1e-15));     // per m2 -> per ft2
  try {
    report::display_units("metric");
    FAIL("refused");
  } catch (const scenario::InputError& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains("--units") && Catch::Contains("metric") && Catch::Contains("us"));
  }

  std::string text = kMower + kStones + "[[field.planes]]\nname = \"path\"\nside = \"left\"\ndistance = \"2.5 m\"\n";
  text.replace(text.find("objects_simulated = 4000"), 24, "objects_simulated = 1500");
  const auto s = read(text);
  const field::FieldSimulator sim(s);
  const auto run = field::run_hazard(sim, 2);
  const auto sum = field::summarise(sim, run);
  const double range = run.strata.front().layout.range;
  const std::string in_si = report::hazard_text(sum, range), in_us = report::hazard_text(sum, range, us);
  CHECK(in_si == report::hazard_text(sum, range, si));
  // A distance beyond the curves names the field's range, as the page does, not the last
  // curve point (a cell short of it).
  // (Ahead and behind, the curves' last point is a whole cell short: 99 m of 100.)
  auto beyond = sum;
  for (auto& d : beyond.directions) d.beyond_range = true, d.upper_beyond_range = false;
  const std::string beyond_text = report::hazard_text(beyond, range), said = fmt::format("beyond {:.0f} m (the range)", range);
  std::size_t times = 0;
  for (std::size_t at = beyond_text.find(said); at != std::string::npos; at = beyond_text.find(said, at + 1)) ++times;
  CHECK(times == beyond.directions.size());
  CHECK(std::any_of(beyond.directions.begin(), beyond.directions.end(),
                    [&](const auto& d) { return fmt::format("{:.0f}", d.distance.back()) != fmt::format("{:.0f}", range); }));
  CHECK_THAT(in_si, Catch::Contains("per km mowed") && Catch::Contains("left 2.5 m"));
  // Each figure converted, not relabelled: the plane's rate, the cut, the speed, the plane's place.
  const auto& path = sum.planes.back();
  CHECK_THAT(in_us, Catch::Contains(fmt::format("{:.3g} hazardous per mile mowed", 1.609344 * path.hazardous_per_km.value)));
  CHECK_THAT(in_us, Catch::Contains(fmt::format("({:.2f} ft cut)", sum.cut_width / 0.3048)));
  CHECK_THAT(in_us, Catch::Contains(fmt::format("{:.0f} mph mean", sum.exit_speed_mean / 0.44704)));
  CHECK_THAT(in_us, Catch::Contains("left 8.2 ft"));
  CHECK_THAT(in_us, !Catch::Contains(" m/s") && !Catch::Contains("per km") && !Catch::Contains(" m)"));
  const auto result = report::hazard_json(sim, run, sum, {});
  const std::string page = report::hazard_html(result, us);
  CHECK_THAT(page, Catch::Contains("at least 58.3 ft-lb") && Catch::Contains("one per 600 ft&sup2;") && Catch::Contains("distance from the mower (ft)") &&
                       Catch::Contains("hazard.json and hazard.csv keep SI units") && Catch::Contains("per ft2 of ground"));
  CHECK_THAT(page, !Catch::Contains("(m)") && !Catch::Contains(" m/s") && !Catch::Contains("per km"));
  CHECK(report::hazard_html(result) == report::hazard_html(result, si));
  // The page is drawn from hazard.json alone: the saved file (written and read back) draws the same page.
  CHECK(report::hazard_html(nlohmann::ordered_json::parse(report::json_text(result)), us) == page);
}

TEST_CASE("report: a page's table writes its header and rows as given, each cell once", "[report]") {
  report::HtmlTable t({"kind", "met per km"});
  t.row({"gravel", "1.5e+04"}).row({"<b>cobble</b>", ""});
  CHECK(t.html() ==
        "<table><tr><th>kind</th><th>met per km</th></tr>\n<tr><td>gravel</td><td>1.5e+04</td></tr>\n"
        "<tr><td><b>cobble</b></td><td></td></tr>\n</table>\n");
  CHECK(report::HtmlTable({"a"}).html() == "<table><tr><th>a</th></tr>\n</table>\n");
  // A table of figures, in sections, with a cell across columns.
  report::HtmlTable n("numbers", {"design", "verdict", "P(pass)"});
  n.row({"1", report::HtmlCell::spanning(2, "no verdict")});
  CHECK(n.html() ==
        "<table class=\"numbers\"><thead><tr><th>design</th><th>verdict</th><th>P(pass)</th></tr></thead><tbody>\n"
        "<tr><td>1</td><td colspan=\"2\">no verdict</td></tr>\n</tbody></table>\n");
  // In sections without a class, a row with attributes, and a list of keys without a header.
  report::HtmlTable a("", {"assumption"});
  a.row({"rigid rod"}, " class=\"deciding\"");
  CHECK(a.html() == "<table><thead><tr><th>assumption</th></tr></thead><tbody>\n<tr class=\"deciding\"><td>rigid rod</td></tr>\n</tbody></table>\n");
  auto k = report::HtmlTable::without_header("keys");
  k.row({"seed", "7"});
  CHECK(k.html() == "<table class=\"keys\"><tbody>\n<tr><td>seed</td><td>7</td></tr>\n</tbody></table>\n");
  report::HtmlTable r("numbers", {"input", "value"});
  r.row({report::HtmlCell::spanning_rows(2, "e"), report::HtmlCell::of_class("verdict-cell", "0.4")}).row({"0.6"});
  CHECK(r.html() == "<table class=\"numbers\"><thead><tr><th>input</th><th>value</th></tr></thead><tbody>\n"
                    "<tr><td rowspan=\"2\">e</td><td class=\"verdict-cell\">0.4</td></tr>\n<tr><td>0.6</td></tr>\n</tbody></table>\n");
}

TEST_CASE("report: hazard.json's plan views hold every cell's count once, the square's edge included", "[field][report]") {
  // A square small beside the throw (25 m, 0.25 m cells: 100 cells a side from the centre), so
  // that hazardous objects come down at its edge and its blocks (3 cells) do not divide it: the
  // last row and column of blocks are cut short, and must still be counted. (4000 objects: at
  // 1500 none came down in the last cell since stones no longer meet the edges inside the flat
  // ground as edges of the steel.)
  std::string text = kMower + kStones;
  text.replace(text.find("[field]\n"), 8, "[field]\nrange = \"25 m\"\ncell = \"0.25 m\"\n");
  const auto s = read(text);
  const field::FieldSimulator sim(s);
  const auto run = field::run_hazard(sim, 2);
  const auto sum = field::summarise(sim, run);
  const auto result = report::hazard_json(sim, run, sum, {});
  const std::vector<double> w = field::weights_per_object(sim, run);
  const auto check = [&](const char* key, std::vector<std::uint64_t> field::HazardTally::*cells) {
    INFO(key);
    double total = 0;  // every cell's count per km mowed, as the plan view weights it
    for (std::size_t k = 0; k < run.strata.size(); ++k)
      for (const auto c : run.strata[k].*cells) total += 1000 * w[k] * static_cast<double>(c);
    const auto& view = result["plan_views"][key];
    const int reach = view["reach_cells"].get<int>(), block = view["block_cells"].get<int>();
    const double cell = view["cell_m"].get<double>();
    double in_blocks = 0;
    for (const auto& b : view["blocks"]) {
      const int bx = b[0].get<int>(), by = b[1].get<int>();
      const int wx = std::min(block, 2 * reach - bx * block), wy = std::min(block, 2 * reach - by * block);
      REQUIRE(wx > 0);
      REQUIRE(wy > 0);
      in_blocks += b[2].get<double>() * (wx * cell) * (wy * cell);
    }
    CHECK(total > 0);
    CHECK(in_blocks == Approx(total).epsilon(1e-9));
    return std::make_pair(reach, block);
  };
  check("first_landings_per_m2_per_km", &field::HazardTally::landings);
  const auto [reach, block] = check("hazardous_impacts_per_m2_per_km", &field::HazardTally::hazardous);
  // The case this test is for: the blocks reach the square's edge and do not divide it.
  CHECK(reach == 100);
  CHECK((2 * reach) % block != 0);
  CHECK(result["plan_views"]["deck_outline_m"].size() >= 3);
}
