// The nail feed and strike detection: statistical tests of the samplers (Kolmogorov-
// Smirnov) and cases whose answer is known.
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
  s.feed.stations = {{0, 0.55, 0.0}};
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

TEST_CASE("feed: strike probability and strike time match the blade's sweep", "[feed][statistics]") {
  // Two edges 180 deg apart sweep a given azimuth every pi / omega. A nail spanning the
  // slab for a window W is struck with probability W omega / pi, at a time uniform on [0, W].
  auto s = straight_scenario();
  s.feed.outlet_speed_max = 0;  // fixed fall speed: a fixed window
  s.feed.tilt_max = 0;
  s.nail.length_tolerance = 0;
  const auto edges = feed::leading_edges(s.spindles[0].blade);
  REQUIRE(edges.size() == 2);
  std::vector<double> times;
  const int n = 20000;
  double window = 0;
  for (int i = 0; i < n; ++i) {
    random::Stream rng(11, 0, static_cast<std::uint64_t>(i), random::Purpose::Feed);
    const auto d = feed::sample_drop(s, i, rng);
    window = feed::slab_window(d, s.spindles[0].geometry);
    if (auto strike = feed::find_strike(d, edges, s.spindles[0].blade.omega, s.spindles[0].geometry)) {
      times.push_back(strike->time);
      CHECK(strike->offset >= -0.5 * d.length - 1e-12);
      CHECK(strike->offset <= 0.5 * d.length + 1e-12);
    }
  }
  const double p = window * s.spindles[0].blade.omega / units::pi;
  const double se = std::sqrt(p * (1 - p) / n);
  CHECK(std::abs(static_cast<double>(times.size()) / n - p) < 4 * se);
  CHECK(test::ks_statistic(times, [&](double t) { return t / window; }) < test::ks_critical_001(times.size()));
}

TEST_CASE("feed: nails outside the tip circle fall through; the contact is where the nail is", "[feed]") {
  auto s = straight_scenario();
  s.feed.stations = {{0, 0.70, 0.5}};  // beyond the 0.6096 m reach
  const auto edges = feed::leading_edges(s.spindles[0].blade);
  int struck = 0;
  for (int i = 0; i < 2000; ++i) {
    random::Stream rng(3, 0, static_cast<std::uint64_t>(i), random::Purpose::Feed);
    struck += feed::find_strike(feed::sample_drop(s, i, rng), edges, s.spindles[0].blade.omega, s.spindles[0].geometry).has_value();
  }
  CHECK(struck == 0);

  // A nail at a known place and a known phase: struck by edge 0 after (azimuth - phase) / omega.
  feed::NailDrop d;
  d.length = 0.0508;
  d.position = {0.5 * std::cos(0.3), 0.5 * std::sin(0.3)};
  d.fall_speed = 0.5;  // slow: long window
  d.blade_phase = 0.25;
  s.spindles[0].geometry.thickness = 0.006;
  const auto strike = feed::find_strike(d, edges, s.spindles[0].blade.omega, s.spindles[0].geometry);
  REQUIRE(strike);
  CHECK(strike->edge == 0);
  CHECK(strike->time == Approx(0.05 / s.spindles[0].blade.omega).epsilon(1e-12));
  CHECK(strike->radius == Approx(0.5));
  CHECK(strike->azimuth == Approx(0.3));
  // The blade's mid-plane lies (fall - thickness/2) above the tip, or the tip is struck.
  const double t = strike->time, fall = 0.5 * t + 0.5 * feed::kGravity * t * t;
  CHECK(strike->offset == Approx(std::max(0.0, fall - 0.003) - 0.0254).epsilon(1e-9));
  d.blade_phase = 0.3 - 0.012 * s.spindles[0].blade.omega;  // struck 12 ms in: the nail has fallen past the mid-plane
  const auto later = feed::find_strike(d, edges, s.spindles[0].blade.omega, s.spindles[0].geometry);
  REQUIRE(later);
  const double t2 = later->time, fall2 = 0.5 * t2 + 0.5 * feed::kGravity * t2 * t2;
  CHECK(t2 == Approx(0.012).epsilon(1e-9));
  CHECK(later->offset == Approx(fall2 - 0.003 - 0.0254).epsilon(1e-9));
}

TEST_CASE("random streams: keyed by (seed, replicate, nail, purpose), independent of order", "[random]") {
  random::Stream a(1, 2, 3, random::Purpose::Feed), b(1, 2, 3, random::Purpose::Feed);
  random::Stream c(1, 2, 4, random::Purpose::Feed), d(1, 2, 3, random::Purpose::Flight);
  const auto a1 = a(), b1 = b();
  CHECK(a1 == b1);
  CHECK(c() != a1);
  CHECK(d() != a1);
  std::vector<double> u;
  random::Stream e(5, 0, 0, random::Purpose::Test);
  for (int i = 0; i < 50000; ++i) u.push_back(e.uniform());
  CHECK(test::ks_statistic(u, [](double x) { return x; }) < test::ks_critical_001(u.size()));
}

// ---- The blade in the scene: sweeps of a moving nail, and strikes ----------------------

#include "feed/spindle.hpp"
#include "random/stream.hpp"

namespace {
feed::Spindle bar_spindle(int sense) {
  blade::Blade b;  // a centred 1.2 m bar: two edges, at 0 and pi, reaching 0.6 m
  b.omega = 100.0;
  b.hub.bar_mass = 10.0;
  b.hub.bar_length = 1.2;
  feed::Spindle sp(b, scenario::BladeGeometry{}, blade::Restitution::constant(0.9));
  sp.sense = sense;
  return sp;
}
}  // namespace

TEST_CASE("blade sweep: a nail in the disc is struck when an edge reaches its azimuth", "[feed][restrike]") {
  for (const int sense : {+1, -1}) {
    const auto sp = bar_spindle(sense);
    // Moving slowly outward along azimuth sense * 1 rad: edge 0 gets there at t = 1 / omega.
    const double az = sense * 1.0;
    const Eigen::Vector3d p0(0.3 * std::cos(az), 0.3 * std::sin(az), sp.height), v(std::cos(az), std::sin(az), 0.0);
    const auto h = feed::first_sweep(sp, 0.0, p0, v, 0.0, 0.05, feed::SweptRod{}, -1.0);
    REQUIRE(h);
    CHECK(h->edge == 0);
    CHECK(h->time == Approx(0.01).margin(1e-9));
    CHECK(h->radius == Approx(0.31).margin(1e-9));
    CHECK(std::remainder(h->azimuth - az, 2 * units::pi) == Approx(0).margin(1e-9));
    // Starting at phase 0.5 rad, the same edge gets there 5 ms sooner.
    CHECK(feed::first_sweep(sp, sense * 0.5, p0, v, 0.0, 0.05, feed::SweptRod{}, -1.0)->time == Approx(0.005).margin(1e-9));
    // Between edges: leaving the window before the edge arrives, the nail is not struck.
    CHECK_FALSE(feed::first_sweep(sp, 0.0, p0, v, 0.0, 0.009, feed::SweptRod{}, -1.0));
    // Above the slab, or beyond the tip circle, nothing strikes it.
    CHECK_FALSE(feed::first_sweep(sp, 0.0, p0 + Eigen::Vector3d(0, 0, 0.01), v, 0.0, 0.05, feed::SweptRod{}, -1.0));
    CHECK_FALSE(feed::first_sweep(sp, 0.0, 2.1 * p0, v, 0.0, 0.05, feed::SweptRod{}, -1.0));
    // ...unless the nail's own height reaches into the slab.
    CHECK(feed::first_sweep(sp, 0.0, p0 + Eigen::Vector3d(0, 0, 0.01), v, 0.0, 0.05, feed::SweptRod{0.04, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()}, -1.0));
  }
}

TEST_CASE("blade sweep: a nail crossing the disc fast is met where the edge and the chord cross", "[feed][restrike]") {
  // A nail flying straight across the disc at 20 m/s, through the axis' neighbourhood:
  // check the answer against a brute-force scan of the edge-to-nail angle.
  const auto sp = bar_spindle(+1);
  random::Stream rng(11, 0, 0, random::Purpose::Test);
  int found = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double a = 2 * units::pi * rng.uniform(), phase = 2 * units::pi * rng.uniform();
    const Eigen::Vector3d p0(0.7 * std::cos(a), 0.7 * std::sin(a), sp.height);
    const double heading = a + units::pi + rng.uniform(-0.6, 0.6);
    const Eigen::Vector3d v(20 * std::cos(heading), 20 * std::sin(heading), 0);
    const auto h = feed::first_sweep(sp, phase, p0, v, 0.0, 0.07, feed::SweptRod{}, -1.0);
    // Brute force: scan the edge-to-nail angle for its first sign change (not the jump at
    // +/-pi), where the edge is faster than the nail along its motion.
    double brute = -1;
    std::vector<double> last(sp.edges.size(), 0.0);
    const double step = 2e-6;
    for (int k = 0; k * step <= 0.07 && brute < 0; ++k) {
      const double t = k * step;
      const Eigen::Vector3d p = p0 + v * t;
      const double r = p.head<2>().norm();
      for (std::size_t e = 0; e < sp.edges.size(); ++e) {
        const double d = std::remainder(phase + sp.edges[e].azimuth + sp.omega() * t - std::atan2(p.y(), p.x()), 2 * units::pi);
        const Eigen::Vector2d tangent(-p.y() / r, p.x() / r);
        if (k > 0 && r <= sp.reach && last[e] * d <= 0 && std::abs(last[e] - d) < 1 && sp.omega() * r > v.head<2>().dot(tangent) &&
            brute < 0)
          brute = t - step * d / (d - last[e]);
        last[e] = d;
      }
    }
    INFO("trial " << trial);
    if (brute < 0) {
      CHECK_FALSE(h);
      continue;
    }
    REQUIRE(h);
    CHECK(h->time == Approx(brute).margin(1e-6));
    ++found;
  }
  CHECK(found > 50);
}

TEST_CASE("blade strike: momentum, restitution and energy hold at every strike", "[feed][restrike][physics]") {
  const auto sp = bar_spindle(+1);
  REQUIRE(sp.lift_angle > 0);  // the default edge is bevelled: the check covers a tilted normal
  random::Stream rng(5, 0, 0, random::Purpose::Test);
  int struck = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    feed::BladeHit h;
    h.radius = rng.uniform(0.05, 0.6);
    h.azimuth = rng.uniform(-3.1, 3.1);
    h.edge = 0;
    feed::NailAtBlade nail;
    nail.mass = 0.002;
    nail.length = 0.05;
    nail.velocity = {rng.uniform(-40, 40), rng.uniform(-40, 40), rng.uniform(-5, 5)};
    nail.spin = {rng.uniform(-500, 500), rng.uniform(-500, 500), 0};
    nail.axis = Eigen::Vector3d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)).normalized();
    nail.spin -= nail.spin.dot(nail.axis) * nail.axis;
    nail.offset = rng.uniform(-0.025, 0.025);
    const auto c = feed::strike(sp, h, nail);
    if (!c) continue;
    ++struck;
    // The contact normal: the edge's direction of travel tilted up by its lift.
    const Eigen::Vector3d n = std::cos(sp.lift_angle) * Eigen::Vector3d(-std::sin(h.azimuth), std::cos(h.azimuth), 0) +
                              std::sin(sp.lift_angle) * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d dv = c->velocity_after - nail.velocity;
    CHECK(c->impulse > 0);
    CHECK(dv.cross(n).norm() < 1e-9 * (1 + dv.norm()));                // impulse along the normal only
    CHECK(nail.mass * dv.dot(n) == Approx(c->impulse).epsilon(1e-9));  // nail's linear momentum
    const double inertia = nail.mass * nail.length * nail.length / 12;
    const Eigen::Vector3d r = nail.offset * nail.axis;
    CHECK((inertia * (c->spin_after - nail.spin) - r.cross(n) * c->impulse).norm() < 1e-9);  // its angular momentum
    CHECK(c->energy_lost >= 0);
    // Restitution at the contact point: separation = e x approach.
    const double before = c->blade_speed_before - (nail.velocity + nail.spin.cross(r)).dot(n);
    const double after = (c->velocity_after + c->spin_after.cross(r)).dot(n) - c->blade_speed_after;
    CHECK(after == Approx(0.9 * before).epsilon(1e-9));
  }
  CHECK(struck > 500);
}

TEST_CASE("blade sweep: a spinning nail is met only at a pass when its turning axis reaches into the slab", "[feed][restrike]") {
  const auto sp = bar_spindle(+1);
  // Centre 12 mm above the blade's mid-plane, a 50 mm nail: lying flat it clears the slab,
  // tilted enough it reaches in. Moving slowly outward, the edges pass it every half turn.
  const double lift = 0.012, length = 0.05;
  const Eigen::Vector3d p0(0.3, 0.0, sp.height + lift), v(1.0, 0.0, 0.0);
  const double needed = (lift - 0.5 * sp.thickness) / (0.5 * length);  // |axis_z| that reaches the slab
  REQUIRE(needed > 0.1);
  REQUIRE(needed < 0.9);
  // Flat and not turning: never struck. Flat, turning slowly about y: struck once tilted enough.
  const feed::SweptRod flat{length, Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero()};
  CHECK_FALSE(feed::first_sweep(sp, 0.3, p0, v, 0.0, 0.2, flat, -1.0));
  for (double spin : {3.0, 40.0, 900.0, 6000.0}) {
    const feed::SweptRod turning{length, Eigen::Vector3d::UnitX(), Eigen::Vector3d(0, spin, 0)};
    const auto h = feed::first_sweep(sp, 0.3, p0, v, 0.0, 0.2, turning, -1.0);
    INFO("spin " << spin << " rad/s");
    REQUIRE(h);
    // At the strike the axis (turned about y by spin * t: z component -sin) reaches the slab ...
    CHECK(std::abs(std::sin(spin * h->time)) >= needed - 1e-9);
    // ... and at every earlier pass of an edge it did not: the edges stand at
    // 0.3 + omega t and 0.3 + omega t + pi, the nail at azimuth 0.
    const double omega = sp.omega();
    for (double t_pass = (units::pi - 0.3) / omega; t_pass < h->time - 1e-9; t_pass += units::pi / omega)
      CHECK(std::abs(std::sin(spin * t_pass)) < needed);
  }
}
