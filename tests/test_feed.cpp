// The nail feed: statistical tests of its samplers (Kolmogorov-Smirnov), and the keyed
// random streams. The strike is tests/test_strike.cpp's.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "feed/feed.hpp"
#include "stats_check.hpp"
#include "units/quantity.hpp"

using namespace j232;

namespace {
scenario::Scenario straight_scenario() {
  scenario::Scenario s;
  s.spindles[0].blade.omega = 1000 * units::rpm;
  s.spindles[0].blade.hub.bar_mass = 10;
  s.spindles[0].blade.hub.bar_length = 1.2192;  // centred: two edges, 24 in reach
  s.feed.stations = std::vector<scenario::FeedStation>{{0, 0.55, 0.0}};
  return s;
}
constexpr double kTwoPi = 2 * units::pi;
}  // namespace

TEST_CASE("feed: blade phase, outlet position and tilt follow their distributions (KS)", "[feed][statistics]") {
  const auto s = straight_scenario();
  std::vector<double> phase, outlet_r2, cos_tilt, speed;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    random::Stream rng(7, 0, static_cast<std::uint64_t>(i), random::Purpose::Feed);
    const auto d = feed::sample_drop(s, i, rng);
    phase.push_back(d.blade_phase);
    const Eigen::Vector2d off = d.position - Eigen::Vector2d(0.55, 0.0);
    outlet_r2.push_back(off.squaredNorm() / std::pow(0.5 * s.feed.outlet_diameter, 2));
    cos_tilt.push_back(d.axis.z());
    speed.push_back(d.fall_speed);
  }
  const double crit = test::ks_critical_001(n);
  CHECK(test::ks_statistic(phase, [](double x) { return x / kTwoPi; }) < crit);
  // Uniform over the outlet disc: (r / R)^2 is uniform on [0, 1].
  CHECK(test::ks_statistic(outlet_r2, [](double x) { return x; }) < crit);
  // Uniform over the spherical cap: cos(tilt) uniform on [cos(max), 1].
  const double c0 = std::cos(s.feed.tilt_max);
  CHECK(test::ks_statistic(cos_tilt, [&](double x) { return (x - c0) / (1 - c0); }) < crit);
  // Fall speed: v^2 = v0^2 + 2 g h with v0 uniform on [0, vmax].
  const double h = s.feed.drop_height, vmax = s.feed.outlet_speed_max, g = feed::kGravity;
  CHECK(test::ks_statistic(speed, [&](double v) { return std::sqrt(std::max(0.0, v * v - 2 * g * h)) / vmax; }) < crit);
}

TEST_CASE("feed: a mis-sampled phase fails the KS test (the test has teeth)", "[feed][statistics]") {
  std::vector<double> skewed;
  for (int i = 0; i < 20000; ++i) {
    random::Stream rng(7, 0, static_cast<std::uint64_t>(i), random::Purpose::Test);
    skewed.push_back(kTwoPi * std::pow(rng.uniform(), 1.05));
  }
  CHECK(test::ks_statistic(skewed, [](double x) { return x / kTwoPi; }) > test::ks_critical_001(20000));
}

TEST_CASE("random streams: keyed by (seed, replicate, nail, purpose), independent of order", "[random]") {
  random::Stream a(1, 2, 3, random::Purpose::Feed), b(1, 2, 3, random::Purpose::Feed);
  random::Stream c(1, 2, 4, random::Purpose::Feed), d(1, 2, 3, random::Purpose::Roughness);
  const auto a1 = a(), b1 = b();
  CHECK(a1 == b1);
  CHECK(c() != a1);
  CHECK(d() != a1);
  std::vector<double> u;
  random::Stream e(5, 0, 0, random::Purpose::Test);
  for (int i = 0; i < 50000; ++i) u.push_back(e.uniform());
  CHECK(test::ks_statistic(u, [](double x) { return x; }) < test::ks_critical_001(u.size()));
}

TEST_CASE("random streams: a flight event's draw depends on its number among its purpose's events, not on what came before", "[random]") {
  // Two histories of one nail: the second meets two guards before its first rough bounce.
  random::EventDraws one(7, 3, 11), two(7, 3, 11);
  const double rough_one = one.next(random::Purpose::Roughness).uniform();
  two.next(random::Purpose::GuardPass), two.next(random::Purpose::GuardPass);
  CHECK(two.next(random::Purpose::Roughness).uniform() == rough_one);
  // ...and its second guard draw is the other's second, however many bounces came between.
  random::EventDraws three(7, 3, 11), four(7, 3, 11);
  const double first_guard = three.next(random::Purpose::GuardPass).uniform();
  four.next(random::Purpose::GuardPass);
  for (int i = 0; i < 5; ++i) four.next(random::Purpose::Roughness);
  const double second_three = three.next(random::Purpose::GuardPass).uniform();
  CHECK(four.next(random::Purpose::GuardPass).uniform() == second_three);
  CHECK(second_three != first_guard);  // the second guard is not the first again
  // Events of one purpose are independent of each other and uniform.
  std::vector<double> u;
  random::EventDraws many(5, 0, 0);
  for (int i = 0; i < 50000; ++i) u.push_back(many.next(random::Purpose::Roughness).uniform());
  CHECK(test::ks_statistic(u, [](double x) { return x; }) < test::ks_critical_001(u.size()));
  // Different nails, replicates and seeds draw differently for the same event.
  const double base = random::EventDraws(1, 2, 3).next(random::Purpose::GuardPass).uniform();
  CHECK(random::EventDraws(1, 2, 4).next(random::Purpose::GuardPass).uniform() != base);
  CHECK(random::EventDraws(1, 3, 3).next(random::Purpose::GuardPass).uniform() != base);
  CHECK(random::EventDraws(2, 2, 3).next(random::Purpose::GuardPass).uniform() != base);
}
