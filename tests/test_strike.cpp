// The strike stage: the blade's section, the contact search against a fixed-step
// reference, and the impulse's invariants (momentum about the spindle and each pivot,
// no energy created, the report's central impact as its frictionless limit).
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "blade/impact.hpp"
#include "feed/feed.hpp"
#include "flight/launch.hpp"
#include "random_blades.hpp"
#include "stats_check.hpp"
#include "strike/contact_search.hpp"
#include "strike/impulse.hpp"
#include "units/quantity.hpp"

using namespace j232;
using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

namespace {

// A straight 48 in bar centred on the spindle (two edges, 24 in reach) at 1000 rpm.
scenario::Scenario bar_scenario() {
  scenario::Scenario s;
  s.spindles[0].blade.omega = 1000 * units::rpm;
  s.spindles[0].blade.hub.bar_mass = 10;
  s.spindles[0].blade.hub.bar_length = 1.2192;
  s.feed.stations = std::vector<scenario::FeedStation>{{0, 0.55, 0.0}};
  return s;
}

// The report's pivoted blade with a free hub: a 24 in hub bar (11 lb) and a 12 in link
// (5.5 lb) pinned at each end, 1000 rpm, so impulses move the hub and the links.
blade::Blade pivoted_blade() {
  blade::Blade b;
  b.omega = 1000 * units::rpm;
  b.hub.bar_mass = 11 * 0.45359237;
  b.hub.bar_length = 0.6096;
  b.hub.drive_inertia = 0.05;
  for (const double azimuth : {0.0, units::pi}) {
    blade::Arm arm;
    arm.azimuth = azimuth;
    arm.pivot_radius = 0.3048;
    blade::Link link;
    link.length = 0.3048, link.mass = 5.5 * 0.45359237;
    arm.links.push_back(link);
    b.arms.push_back(arm);
  }
  return b;
}

strike::Spindle spindle(const scenario::Scenario& s) { return strike::Spindle(s.spindles[0].blade, s.spindles[0].geometry, s.restitution); }

// The half-angle ahead of an arm within which the search's window draws a body of reach
// `reach` whose centre is `r` from the axis (as the search bounds it, at 3/4 of r).
double search_window(double reach, double r) {
  const double x = (reach + 1e-4) / (0.75 * r);
  return x / std::sqrt(1 - x * x) + strike::kCoarseAtan2Error;
}

// An upright nail falling past the blade at (0.5, 0), its tip `depth` below the top face
// when the leading edge (phase -0.2 rad ahead of it... behind it) is about to reach it.
strike::Motion upright_nail(double tip_below_top, const strike::Spindle& sp, const projectile::Projectile& nail) {
  strike::Motion m;
  const double top = sp.height + 0.5 * sp.section.shape().thickness;
  m.p0 = {0.5, 0.0, top - tip_below_top + 0.5 * nail.length};
  m.v0 = {0.0, 0.0, -2.5};
  m.a = {0.0, 0.0, -feed::kGravity};
  m.axis0 = Vec3::UnitZ();
  return m;
}

}  // namespace

TEST_CASE("blade section: the plate, its bevel and sail as convex polygons", "[strike][geometry]") {
  strike::EdgeShape shape;
  shape.thickness = 0.006, shape.width = 0.1, shape.bevel_angle = 30 * units::degree, shape.bevel_on_top = true;
  const strike::BladeSection top(shape);
  REQUIRE(top.parts() == 1);
  // A point ahead of the sharp edge (on the bottom face) at its height: 10 mm off, normal forward.
  auto a = top.approach(Vec2(0.01, -0.003), Vec2(0.01, -0.003));
  CHECK(a.distance == Approx(0.01));
  CHECK(a.normal.x() == Approx(1.0));
  // Above the bevel face: its normal leans forward by the bevel angle from straight up.
  const Vec2 on_bevel(-0.5 * 0.006 / std::tan(30 * units::degree), 0.0);
  const Vec2 n(std::sin(30 * units::degree), std::cos(30 * units::degree));
  a = top.approach(on_bevel + 0.002 * n, on_bevel + 0.002 * n);
  CHECK(a.distance == Approx(0.002));
  CHECK(a.normal.x() == Approx(n.x()));
  CHECK(a.normal.y() == Approx(n.y()));
  // A vertical segment in front of a square edge touches it along the overlap: its middle.
  shape.bevel_angle = 90 * units::degree;
  const strike::BladeSection square(shape);
  a = square.approach(Vec2(0.002, -0.02), Vec2(0.002, 0.001));
  CHECK(a.distance == Approx(0.002));
  CHECK(a.on_section.y() == Approx(-0.001).margin(1e-12));  // the overlap is w in [-3, 1] mm
  // Overlap reports zero distance.
  CHECK(square.approach(Vec2(-0.01, -0.02), Vec2(-0.01, 0.02)).distance == 0);
  // The sail rises behind the width.
  shape.sail_height = 0.03, shape.sail_angle = 45 * units::degree;
  const strike::BladeSection sailed(shape);
  REQUIRE(sailed.parts() == 2);
  CHECK(sailed.top() == Approx(0.033));
  a = sailed.approach(Vec2(-0.115 + 0.002 * std::sqrt(0.5), 0.018 + 0.002 * std::sqrt(0.5)), Vec2(-0.115, 0.06));
  CHECK(a.distance > 0);
}

TEST_CASE("contact search: its coarse atan2 and its turning axis", "[strike][search]") {
  // The azimuth bound widens the arm's window by kCoarseAtan2Error: the approximation must
  // stay inside it everywhere, on the axes and at the octant boundaries too.
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double y = u(gen) * std::pow(10.0, 3 * u(gen)), x = u(gen) * std::pow(10.0, 3 * u(gen));
    worst = std::max(worst, std::abs(strike::coarse_atan2(y, x) - std::atan2(y, x)));
  }
  for (const double a : {0.0, 0.25, 0.5, 0.75, 1.0, -0.25, -0.5, -0.75})
    worst = std::max(worst, std::abs(strike::coarse_atan2(std::sin(a * units::pi), std::cos(a * units::pi)) -
                                     std::atan2(std::sin(a * units::pi), std::cos(a * units::pi))));
  CHECK(worst < 0.6 * strike::kCoarseAtan2Error);
  CHECK(strike::coarse_atan2(0.0, 0.0) == 0.0);
  // The turning axis: unit, the angle from its start w dt (for an axis across the spin),
  // its component along the spin fixed, and exactly its start at dt = 0.
  for (int i = 0; i < 1000; ++i) {
    const Vec3 axis = Vec3(u(gen), u(gen), u(gen)).normalized(), spin = 3000 * Vec3(u(gen), u(gen), u(gen));
    const strike::Turning turning(axis, spin);
    const double dt = 1e-3 * u(gen);
    const Vec3 a = turning.at(dt);
    CHECK(a.norm() == Approx(1.0).epsilon(1e-12));
    CHECK(a.dot(spin) == Approx(axis.dot(spin)).margin(1e-9));
    const Vec3 k = spin.normalized();
    const Vec3 p0 = axis - axis.dot(k) * k, p1 = a - a.dot(k) * k;
    const double turned = std::atan2(k.dot(p0.cross(p1)), p0.dot(p1));
    CHECK(std::remainder(turned - spin.norm() * dt, units::two_pi) == Approx(0.0).margin(1e-9));
    CHECK(turning.at(0.0) == axis);
  }
}

TEST_CASE("launch: the turning blade throws a nail from its contact; a nail moving with the blade is not thrown", "[strike][physics]") {
  const auto s = bar_scenario();
  const auto sp = spindle(s);
  const auto nail = projectile::Projectile::capsule(0.0508, 0.00251, 0.002);
  const auto m = upright_nail(0.01, sp, nail);
  strike::SearchStats stats;
  const auto c = strike::first_contact(sp, -0.1, nail, m, m.t0 + 0.02, stats);
  REQUIRE(c);
  const Vec3 coming = m.velocity(c->time);
  const flight::Launch l = flight::launch(sp, *c, nail, coming);
  REQUIRE(l.result == flight::Launch::Result::Thrown);
  // The body leaves from the contact, at its time, with the impulse's velocity and the spin
  // across its axis (a rod's flight follows its axis), and more energy than it came with.
  const auto direct = strike::strike(sp, *c, nail, coming, Vec3::Zero());
  CHECK(l.body.position == c->centre);
  CHECK(l.body.axis == c->axis);
  CHECK(l.body.time == c->time);
  CHECK(l.body.velocity == direct.velocity_after);
  CHECK(std::abs(l.body.spin.dot(l.body.axis)) < 1e-9 * (1 + l.body.spin.norm()));
  CHECK((l.body.spin - (direct.spin_after - direct.spin_after.dot(c->axis) * c->axis)).norm() < 1e-12 * (1 + l.body.spin.norm()));
  CHECK(l.body.velocity.squaredNorm() > coming.squaredNorm());
  // Moving with the blade's point there, it is not approaching: not thrown, no body.
  const flight::Launch with_blade = flight::launch(sp, *c, nail, sp.velocity_at(c->point));
  CHECK(with_blade.result == flight::Launch::Result::NotThrown);
  CHECK_FALSE(with_blade.hit.approaching);
  // A tilted nail's strike spins it about its own axis too; the flight keeps only the spin
  // across the axis (a rod's flight follows its axis).
  auto tilted = m;
  tilted.axis0 = Vec3(0.3, 0.4, 1.0).normalized();
  const auto ct = strike::first_contact(sp, -0.1, nail, tilted, tilted.t0 + 0.02, stats);
  REQUIRE(ct);
  const auto direct_tilted = strike::strike(sp, *ct, nail, tilted.velocity(ct->time), Vec3::Zero());
  REQUIRE(std::abs(direct_tilted.spin_after.dot(ct->axis)) > 1e-3 * direct_tilted.spin_after.norm());
  const flight::Launch lt = flight::launch(sp, *ct, nail, tilted.velocity(ct->time));
  REQUIRE(lt.result == flight::Launch::Result::Thrown);
  CHECK(std::abs(lt.body.spin.dot(lt.body.axis)) < 1e-9 * lt.body.spin.norm());
  // A nail dropped flat onto a stopped blade approaches it but gains no energy: not thrown.
  auto still = s;
  still.spindles[0].blade.omega = 0;
  const auto stopped = spindle(still);
  strike::Motion flat;
  flat.p0 = {0.5, 0.0, stopped.height + 0.5 * stopped.section.shape().thickness + nail.radius() + 0.01};
  flat.v0 = {0.0, 0.0, -2.0};
  flat.a = {0.0, 0.0, -9.81};
  flat.axis0 = Vec3::UnitY();
  const auto cs = strike::first_contact(stopped, 0.0, nail, flat, 0.1, stats);
  REQUIRE(cs);
  const flight::Launch dropped = flight::launch(stopped, *cs, nail, flat.velocity(cs->time));
  CHECK(dropped.hit.approaching);
  CHECK(dropped.result == flight::Launch::Result::NotThrown);
  // An impulse that is no number (a body of no finite mass) is cut off, never counted as not
  // struck: the finite check comes before the energy test, which a NaN would fail.
  const auto no_number = projectile::Projectile::capsule(0.0508, 0.00251, std::nan(""));
  const flight::Launch broken = flight::launch(sp, *c, no_number, coming);
  CHECK(broken.result == flight::Launch::Result::NonFinite);
}

TEST_CASE("strike: an upright nail struck by a frictionless square edge gets no vertical impulse", "[strike][physics]") {
  auto s = bar_scenario();
  s.spindles[0].geometry.edge.bevel_angle = 90 * units::degree;
  s.spindles[0].geometry.edge.friction = 0.0;
  const auto sp = spindle(s);
  const auto nail = projectile::Projectile::capsule(0.0508, 0.00251, 0.002);
  for (const double depth : {0.002, 0.01, 0.03}) {
    const auto m = upright_nail(depth, sp, nail);
    strike::SearchStats stats;
    // The edge at 0 rad stands 0.1 rad behind the nail's azimuth at time 0.
    const auto c = strike::first_contact(sp, -0.1, nail, m, m.t0 + 0.02, stats);
    REQUIRE(c);
    CHECK(std::abs(c->normal.z()) < 1e-9);
    const auto out = strike::strike(sp, *c, nail, m.velocity(c->time), Vec3::Zero());
    REQUIRE(out.approaching);
    CHECK(std::abs(out.solution.impulse.z()) < 1e-12);
    CHECK(out.velocity_after.z() == Approx(m.velocity(c->time).z()).margin(1e-12));
  }
  SECTION("friction against the falling nail lifts it; a top bevel under its tip lifts it more") {
    s.spindles[0].geometry.edge.friction = 0.4;
    const auto rough = spindle(s);
    const auto m = upright_nail(0.03, rough, nail);
    strike::SearchStats stats;
    const auto c = strike::first_contact(rough, -0.1, nail, m, m.t0 + 0.02, stats);
    REQUIRE(c);
    const auto out = strike::strike(rough, *c, nail, m.velocity(c->time), Vec3::Zero());
    CHECK(out.solution.impulse.z() > 0);
    s.spindles[0].geometry.edge.bevel_angle = 30 * units::degree;
    s.spindles[0].geometry.edge.friction = 0.0;
    const auto bevelled = spindle(s);
    const auto tip_in_bevel = upright_nail(0.003, bevelled, nail);  // the tip 3 mm into the 6 mm plate
    const auto b = strike::first_contact(bevelled, -0.1, nail, tip_in_bevel, tip_in_bevel.t0 + 0.02, stats);
    REQUIRE(b);
    CHECK(b->normal.z() == Approx(std::cos(30 * units::degree)).epsilon(1e-6));  // the bevel face's normal
  }
}

TEST_CASE("impulse (the legacy Poisson law): no energy created, Coulomb's cone respected, Poisson's restitution", "[strike][physics]") {
  std::mt19937_64 rng(17);
  const auto u = [&](double lo, double hi) { return test::uniform(rng, lo, hi); };
  int sliding = 0, lowered = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const auto nail = projectile::Projectile::capsule(u(0.01, 0.08), u(0.001, 0.005), u(0.001, 0.01));
    const Vec3 axis = Vec3(u(-1, 1), u(-1, 1), u(-1, 1)).normalized();
    const Vec3 r = u(-0.5, 0.5) * nail.length * axis + nail.radius() * axis.unitOrthogonal();
    const Eigen::Matrix3d inv_i = strike::inverse_inertia(nail, axis);
    Eigen::Matrix3d R;
    R << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    Eigen::Matrix3d K = Eigen::Matrix3d::Identity() / nail.mass - R * inv_i * R;
    const Vec3 t_dir = Vec3(u(-1, 1), u(-1, 1), 0).normalized();
    K += (1.0 / u(0.05, 50)) * t_dir * t_dir.transpose();  // a blade giving way along its motion
    const Vec3 n = Vec3(u(-1, 1), u(-1, 1), u(-1, 1)).normalized();
    Vec3 v_rel = Vec3(u(-100, 100), u(-100, 100), u(-100, 100));
    if (v_rel.dot(n) >= 0) v_rel -= (v_rel.dot(n) + u(0.1, 50)) * n;
    const double mu = u(0, 1.5), e = u(0, 1);
    const auto sol = strike::solve_impulse_poisson(K, v_rel, n, blade::Restitution::constant(e), mu);
    const double scale = 0.5 * v_rel.dot(K.ldlt().solve(v_rel));
    CHECK(sol.energy_change <= 1e-9 * scale);
    const double pn = sol.impulse.dot(n);
    CHECK(pn >= 0);
    CHECK((sol.impulse - pn * n).norm() <= mu * pn * (1 + 1e-9) + 1e-15);
    // Poisson's rule: sticking, the normal impulse is (1 + e) times the compression's (which
    // brings the relative velocity to zero); sliding, the normal separation is e times the
    // approach.
    const Vec3 after = v_rel + K * sol.impulse;
    if (sol.e == Approx(e)) {
      if (sol.sticking)
        CHECK(pn == Approx((1 + e) * K.ldlt().solve(Vec3(-v_rel)).dot(n)).epsilon(1e-7));
      else
        CHECK(after.dot(n) == Approx(-e * v_rel.dot(n)).epsilon(1e-7));
    }
    if (!sol.sticking) ++sliding;
    if (sol.e < e - 1e-9) ++lowered;
  }
  CHECK(sliding > 1000);  // both regimes are exercised
  INFO("restitution lowered to create no energy in " << lowered << " of 20000");
  CHECK(lowered < 20000);
}

namespace {
// A random contact as the blade and the scene make them: a capsule's compliance at a point
// of its surface, maybe a blade giving way along one direction, an approaching velocity.
struct RandomContact {
  Eigen::Matrix3d K;
  Vec3 n, v_rel;
  double mu, e;
};
RandomContact random_contact(std::mt19937_64& rng, bool blade) {
  const auto u = [&](double lo, double hi) { return test::uniform(rng, lo, hi); };
  const auto nail = projectile::Projectile::capsule(u(0.01, 0.08), u(0.001, 0.005), u(0.001, 0.01));
  const Vec3 axis = Vec3(u(-1, 1), u(-1, 1), u(-1, 1)).normalized();
  const Vec3 r = u(-0.5, 0.5) * nail.length * axis + nail.radius() * axis.unitOrthogonal();
  RandomContact c;
  c.K = strike::nail_compliance(nail, strike::inverse_inertia(nail, axis), r);
  if (blade) {
    const Vec3 t_dir = Vec3(u(-1, 1), u(-1, 1), 0).normalized();
    c.K += (1.0 / u(0.05, 50)) * t_dir * t_dir.transpose();
  }
  c.n = Vec3(u(-1, 1), u(-1, 1), u(-1, 1)).normalized();
  c.v_rel = Vec3(u(-100, 100), u(-100, 100), u(-100, 100));
  if (c.v_rel.dot(c.n) >= 0) c.v_rel -= (c.v_rel.dot(c.n) + u(0.1, 50)) * c.n;
  c.mu = u(0, 1.2), c.e = u(0, 1);
  return c;
}

// An independent integration of Stronge's law, written apart from the code under test: fixed
// small steps of the normal impulse, forward Euler on v(p), friction -mu u/|u| while slipping,
// the sticking rate (by a 3x3 solve restricted to the tangent plane) while friction can hold,
// a restart along the flow's outward ray (by a scan of directions) when it cannot,
// stopped when the restitution work reaches e^2 times the compression's.
Vec3 reference_stronge(const RandomContact& c, int steps) {
  const Vec3& n = c.n;
  Vec3 v = c.v_rel, P = Vec3::Zero();
  const double p_total_guess = -(1 + c.e) * c.v_rel.dot(n) / n.dot(c.K * n);
  const double dp = 4 * p_total_guess / steps;
  double wc = 0, wr = 0;
  bool compressing = true;
  // The sticking rate: the tangential impulse per unit normal keeping the slip nil.
  const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  Eigen::Matrix2d A;
  A << t1.dot(c.K * t1), t1.dot(c.K * t2), t2.dot(c.K * t1), t2.dot(c.K * t2);
  const Eigen::Vector2d b(t1.dot(c.K * n), t2.dot(c.K * n));
  const Eigen::Vector2d st = -A.colPivHouseholderQr().solve(b);
  const Vec3 stick = st.x() * t1 + st.y() * t2;
  // A slip restarting from rest (friction cannot hold it) starts along the direction d its
  // own flow keeps, K (n - mu d) along +d in the tangent plane: found by scanning 20 000
  // directions for sign changes of d x (K (n - mu d)), each refined by bisection.
  Vec3 restart = stick.norm() > 0 ? Vec3(-stick.normalized()) : t1;
  if (stick.norm() > c.mu) {
    const auto dir = [&](double a) { return Vec3(std::cos(a) * t1 + std::sin(a) * t2); };
    const auto cross = [&](double a) { return n.dot(dir(a).cross(c.K * (n - c.mu * dir(a)))); };
    constexpr int kCells = 20000;
    for (int i = 0; i < kCells; ++i) {
      double lo = 2 * M_PI * i / kCells, hi = 2 * M_PI * (i + 1) / kCells;
      if ((cross(lo) <= 0) == (cross(hi) <= 0)) continue;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        ((cross(mid) <= 0) == (cross(lo) <= 0) ? lo : hi) = mid;
      }
      const Vec3 d = dir(0.5 * (lo + hi));
      if (d.dot(c.K * (n - c.mu * d)) > 0) restart = d;
    }
  }
  for (int i = 0; i < 40 * steps; ++i) {
    const Vec3 slip = v - v.dot(n) * n;
    Vec3 f;
    const double tiny = 1e-9 * c.v_rel.norm();
    if (slip.norm() > tiny) f = -c.mu * slip.normalized();
    else if (stick.norm() <= c.mu) f = stick;
    else f = -c.mu * restart;
    const Vec3 dP = (n + f) * dp;
    const double vn0 = v.dot(n);
    Vec3 v_next = v + c.K * dP;
    // Do not step the slip through zero: stop it there.
    const Vec3 slip_next = v_next - v_next.dot(n) * n;
    if (slip.norm() > tiny && slip_next.dot(slip) < 0) v_next -= slip_next;
    const double vn1 = v_next.dot(n);
    const double w = 0.5 * (vn0 + vn1) * dp;
    if (compressing && vn1 >= 0) {
      compressing = false;
      if (c.e == 0) { P += dP; break; }
    }
    (compressing ? wc : wr) += w;
    P += dP, v = v_next;
    if (!compressing && wr >= c.e * c.e * -wc) break;
  }
  return P;
}
}  // namespace

TEST_CASE("impulse (Stronge's energetic law): frictionless it is Newton's, for a point mass the known slip, never energy", "[strike][physics]") {
  std::mt19937_64 rng(31);
  for (int trial = 0; trial < 5000; ++trial) {
    RandomContact c = random_contact(rng, trial % 2 == 0);
    // Frictionless: the normal impulse is (1 + e) times the compression's, exactly.
    const auto frictionless = strike::solve_impulse_energetic(c.K, c.v_rel, c.n, c.e, 0.0);
    const Vec3 newton = (-(1 + c.e) * c.v_rel.dot(c.n) / c.n.dot(c.K * c.n)) * c.n;
    CHECK((frictionless.impulse - newton).norm() <= 1e-12 * newton.norm());
    // A point mass: the slip falls by mu (1 + e) |v_n| along its own direction, or stops.
    const double m = test::uniform(rng, 0.001, 0.01);
    const Eigen::Matrix3d K = Eigen::Matrix3d::Identity() / m;
    const auto point = strike::solve_impulse_energetic(K, c.v_rel, c.n, c.e, c.mu);
    const Vec3 after = c.v_rel + K * point.impulse, slip0 = c.v_rel - c.v_rel.dot(c.n) * c.n;
    const double fall = c.mu * (1 + c.e) * -c.v_rel.dot(c.n);
    const Vec3 expected_slip = slip0.norm() > fall ? Vec3(slip0 * (1 - fall / slip0.norm())) : Vec3::Zero();
    CHECK((after - after.dot(c.n) * c.n - expected_slip).norm() <= 1e-9 * c.v_rel.norm());
    CHECK(after.dot(c.n) == Approx(-c.e * c.v_rel.dot(c.n)).epsilon(1e-9));
    // With friction, any contact: no energy created, Coulomb's cone, a pushing impulse.
    const auto sol = strike::solve_impulse_energetic(c.K, c.v_rel, c.n, c.e, c.mu);
    const double scale = 0.5 * c.v_rel.dot(c.K.ldlt().solve(c.v_rel));
    CHECK(sol.energy_change <= 1e-9 * scale);
    const double pn = sol.impulse.dot(c.n);
    CHECK(pn >= 0);
    CHECK((sol.impulse - pn * c.n).norm() <= c.mu * pn * (1 + 1e-6) + 1e-15);
  }
}

TEST_CASE("impulse (Stronge's energetic law) agrees with an independent fine integration along the normal impulse", "[strike][physics]") {
  std::mt19937_64 rng(37);
  std::vector<double> errors, poisson_errors;
  int reversals = 0;
  for (int trial = 0; trial < 400; ++trial) {
    RandomContact c = random_contact(rng, trial % 2 == 0);
    c.mu = 0.4;
    const Vec3 reference = reference_stronge(c, 200000);
    const Vec3 ours = strike::solve_impulse_energetic(c.K, c.v_rel, c.n, c.e, c.mu).impulse;
    const Vec3 legacy = strike::solve_impulse_poisson(c.K, c.v_rel, c.n, blade::Restitution::constant(c.e), c.mu).impulse;
    // The change of the contact point's relative velocity, as a share of the approach speed.
    const double speed = c.v_rel.norm();
    errors.push_back((c.K * (ours - reference)).norm() / speed);
    poisson_errors.push_back((c.K * (legacy - reference)).norm() / speed);
    const Vec3 slip0 = c.v_rel - c.v_rel.dot(c.n) * c.n, after = c.v_rel + c.K * ours, slip1 = after - after.dot(c.n) * c.n;
    reversals += slip1.dot(slip0) < -1e-6 * speed * speed;
  }
  std::sort(errors.begin(), errors.end());
  std::sort(poisson_errors.begin(), poisson_errors.end());
  INFO("energetic law against the reference: median " << errors[200] << ", 99th percentile " << errors[396] << ", worst " << errors.back()
                                                     << "; the legacy Poisson law: median " << poisson_errors[200] << ", 90th "
                                                     << poisson_errors[360] << "; slips turned back: " << reversals);
  CHECK(errors[396] < 1e-3);  // the two integrations agree to the reference's and the slip-turn step's error
  CHECK(errors.back() < 3e-3);
  CHECK(poisson_errors[360] > 10 * errors[360]);  // the legacy law is measurably not this one
}

TEST_CASE("impulse (Stronge's energetic law): a ball's contacts in closed form, as the fine integration and the 5/7 rule give", "[strike][physics]") {
  // A ball's contact couples no normal and tangential motion and is isotropic in the tangent
  // plane: the law's closed form is used there. Against the independent integration, and the
  // textbook rolling result: a solid ball without spin landing with its slip stopped leaves
  // with 5/7 of its tangential speed; sliding throughout it loses mu (1 + e) |v_n|.
  std::mt19937_64 rng(41);
  double worst = 0;
  int sticking = 0, sliding = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double d = test::uniform(rng, 0.004, 0.1), m = test::uniform(rng, 0.001, 2.0);
    const projectile::Projectile ball = projectile::Projectile::sphere(d, m);
    const Vec3 n = Vec3(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1), test::uniform(rng, -1, 1)).normalized();
    const Vec3 axis = Vec3(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1), test::uniform(rng, -1, 1)).normalized();
    RandomContact c;
    c.n = n;
    c.K = strike::nail_compliance(ball, strike::inverse_inertia(ball, axis), -0.5 * d * n);
    const Vec3 slip = test::uniform(rng, 0, 30) * n.unitOrthogonal();
    const double vn = -test::uniform(rng, 0.5, 30);
    c.v_rel = vn * n + Eigen::AngleAxisd(test::uniform(rng, 0, 6.3), n) * slip;
    c.e = test::uniform(rng, 0, 1), c.mu = test::uniform(rng, 0.05, 1.0);
    const auto ours = strike::solve_impulse_energetic(c.K, c.v_rel, c.n, c.e, c.mu);
    const Vec3 reference = reference_stronge(c, 100000);
    worst = std::max(worst, (c.K * (ours.impulse - reference)).norm() / c.v_rel.norm());
    // The textbook: the centre's tangential velocity after (no spin before: the contact
    // point's velocity is the centre's).
    const Vec3 v_t = c.v_rel - vn * n, centre_after = c.v_rel + ours.impulse / m;
    const Vec3 t_after = centre_after - centre_after.dot(n) * n;
    const double fall = c.mu * (1 + c.e) * -vn;
    if (v_t.norm() * 2.0 / 7.0 <= fall) {  // stops slipping: rolls away at 5/7
      ++sticking;
      CHECK(ours.sticking);
      CHECK((t_after - 5.0 / 7.0 * v_t).norm() <= 1e-9 * c.v_rel.norm());
    } else {
      ++sliding;
      CHECK_FALSE(ours.sticking);
      CHECK((t_after - (1 - fall / v_t.norm()) * v_t).norm() <= 1e-9 * c.v_rel.norm());
    }
    CHECK(centre_after.dot(n) == Approx(-c.e * vn).epsilon(1e-9));
    CHECK(ours.energy_change <= 0);
  }
  INFO("closed form against the integration: worst " << worst << " of the approach; " << sticking << " sticking, " << sliding << " sliding");
  CHECK(sticking > 30);
  CHECK(sliding > 30);
  CHECK(worst < 1e-3);
}

TEST_CASE("impulse (Stronge's energetic law): a slip passing close by zero creates no energy; a restart keeps its direction", "[strike][physics]") {
  // The independent review's hand case: isotropic K_tt with a small coupling to the normal,
  // the slip heading almost straight at zero (off by 1e-3 to 5e-3 rad), so it passes zero
  // just aside within a step. Friction held along the old slip past its closest approach
  // would do positive work there.
  std::mt19937_64 rng(43);
  int restarts_checked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double m = 0.002, mu = test::uniform(rng, 0.2, 0.8), e = test::uniform(rng, 0.0, 1.0);
    const Vec3 n = Vec3::UnitZ(), t1 = Vec3::UnitX(), t2 = Vec3::UnitY();
    // The slip along t1 changes at k_n - mu u/(m |u|): k_n across it, off in angle.
    const double off = test::uniform(rng, 1e-3, 5e-3) * (trial % 2 ? 1 : -1);
    const double coupling = off * mu / m;
    Eigen::Matrix3d K = Eigen::Matrix3d::Identity() / m;
    K += coupling * (n * t2.transpose() + t2 * n.transpose());
    const double vn = -test::uniform(rng, 1, 30);
    // The slip stops after a fraction of the impulse: mu (1 + e) |vn| times that.
    const double slip = mu * (1 + e) * -vn * test::uniform(rng, 0.1, 0.9);
    const Vec3 v_rel = vn * n + slip * t1;
    const auto sol = strike::solve_impulse_energetic(K, v_rel, n, e, mu);
    const double incoming = 0.5 * v_rel.dot(K.ldlt().solve(v_rel));
    CHECK(sol.energy_change <= 1e-9 * incoming);
    // Coulomb's cone and a pushing impulse.
    const double pn = sol.impulse.dot(n);
    CHECK(pn > 0);
    CHECK((sol.impulse - pn * n).norm() <= mu * pn * (1 + 1e-6));
  }
  // A restart: friction that cannot hold a contact at rest lets the slip start along a
  // direction the flow keeps (k_n - mu K_tt u parallel to +u), checked here on anisotropic K_tt.
  // Half of them strongly anisotropic (condition numbers up to 1e4), where the flow's turn
  // rate changes sign twice within a few degrees and a scan of the circle can miss the ray.
  for (int trial = 0; trial < 2000; ++trial) {
    Eigen::Matrix2d A = Eigen::Matrix2d::Random();
    Eigen::Matrix2d ktt = A * A.transpose() + 0.2 * Eigen::Matrix2d::Identity();
    if (trial % 2) {
      const double turn = test::uniform(rng, 0, M_PI), c = std::cos(turn), s = std::sin(turn);
      Eigen::Matrix2d R;
      R << c, -s, s, c;
      ktt = R * Eigen::Vector2d(1, std::pow(10.0, test::uniform(rng, 1, 4))).asDiagonal() * R.transpose();
    }
    const Vec2 kn = Vec2::Random() * 3;
    const Vec2 stick = -(ktt.inverse() * kn);
    const double mu = test::uniform(rng, 0.05, 0.95) * stick.norm();  // cannot hold: |stick| > mu
    const Vec2 u = strike::restart_direction(kn, ktt, mu, stick);
    const Vec2 g = kn - mu * (ktt * u);
    INFO("kn " << kn.transpose() << " ktt " << ktt << " mu " << mu << " u " << u.transpose());
    REQUIRE(u.norm() == Approx(1).epsilon(1e-12));
    if (std::abs(u.x() * g.y() - u.y() * g.x()) <= 1e-9 * g.norm() && u.dot(g) > 0) ++restarts_checked;
  }
  CHECK(restarts_checked == 2000);
}

TEST_CASE("impulse (Stronge's energetic law): across the sticking limit the impulse is continuous, and found in few steps", "[strike][physics]") {
  // Friction just unable to hold the contact restarts the slip along the flow's outward ray,
  // which tends to the sticking rate's opposite as the margin goes to zero: the impulse just
  // below the limit and just above it (sticking) differ by about the margin. The slip, once
  // small, swings its direction faster than explicit steps can follow: a contact of the 15 ft
  // batwing's chains took 100 000 steps (the step cap is a checked invariant: reaching it
  // aborts). A fixed-step reference is no judge here (it chatters about zero slip: 2.7 %
  // apart between 2e5 and 2e6 steps on that contact), so the check is continuity.
  Eigen::Matrix3d K;
  K << 2825.1666241418015, 4.7429931846377658, -36.990181507018136, 4.7429931846377453, 1851.0415815000424, -51.4762550092927,
      -36.990181507018136, -51.476255009292686, 496.63917948266749;
  const RandomContact seen{K, Vec3(-0.0037492100457783991, 0.99277660559231551, 0.11991895101539427),
                           Vec3(0.26576734451831879, -70.37422584519588, -2.4844435110243324), 0.4, 0.9};
  std::mt19937_64 rng(59);
  double worst_ratio = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    RandomContact c = trial == 0 ? seen : random_contact(rng, trial % 2 == 0);
    const Vec3 t1 = c.n.unitOrthogonal(), t2 = c.n.cross(t1);
    Eigen::Matrix2d A;
    A << t1.dot(c.K * t1), t1.dot(c.K * t2), t2.dot(c.K * t1), t2.dot(c.K * t2);
    const double need = (A.inverse() * Vec2(t1.dot(c.K * c.n), t2.dot(c.K * c.n))).norm();
    if (!(need > 1e-3)) continue;
    const double margin = trial == 0 ? 1 - c.mu / need : std::pow(10.0, test::uniform(rng, -5, -1));
    // Slips of every size, the small ones stopping early.
    if (trial > 0) {
      const double vn = c.v_rel.dot(c.n);
      const Vec3 slip0 = c.v_rel - vn * c.n;
      if (slip0.norm() > 0) c.v_rel = vn * c.n + std::pow(10.0, test::uniform(rng, -4, 1)) * need * -vn * slip0.normalized();
    }
    const auto below = strike::solve_impulse_energetic(c.K, c.v_rel, c.n, c.e, need * (1 - margin));
    const auto above = strike::solve_impulse_energetic(c.K, c.v_rel, c.n, c.e, need * (1 + margin));
    // Apart, as a share of the normal velocity's change; expected: the two frictions differ by
    // 2 margin need, acting over at most the whole normal impulse, through a compliance up to
    // |K| / k_nn times the normal one; plus the stop tolerance (a slip within 1e-4 of the
    // impulse's scale of stopping is taken as stopped).
    const double apart = (c.K * (below.impulse - above.impulse)).norm() / (-c.v_rel.dot(c.n) * (1 + c.e));
    const double expected = 2 * margin * need * c.K.norm() / c.n.dot(c.K * c.n) + 1e-4;
    worst_ratio = std::max(worst_ratio, apart / expected);
    INFO("trial " << trial << " margin " << margin << " apart " << apart << " e " << c.e << " need " << need << " below sticking " << below.sticking
                  << " above sticking " << above.sticking << " slip0/(need vn) " << (c.v_rel - c.v_rel.dot(c.n) * c.n).norm() / (need * -c.v_rel.dot(c.n))
                  << " cond " << A.norm() * A.inverse().norm());
    CHECK(apart <= 2 * expected);
    const double incoming = 0.5 * c.v_rel.dot(c.K.ldlt().solve(c.v_rel));
    CHECK(below.energy_change <= 1e-9 * incoming);
  }
  INFO("the impulses either side of the limit differ by at most " << worst_ratio << " of the expected bound");
  CHECK(worst_ratio <= 2);  // (1.24 measured; 600 before on-ray steps were taken exactly)
}

TEST_CASE("impulse (Stronge's energetic law): a slip on the outward ray just short of sticking never aborts, and creates no energy", "[strike][physics]") {
  // An independent review's adversarial contacts: friction within 1e-8 to 1e-4 of holding
  // the contact, the slip already on the flow's outward ray and just above the stop
  // tolerance. While the test that a ray was found used a round-off bound relative to the
  // slip's own rate (about 1e-22 here, against a round-off of 1e-18), 470 of these 20 000 ran
  // to the step cap (which aborted); with the bound on the rates' scale, none does. Beyond the
  // cap the legacy law's impulse is taken (flagged), which creates no energy either.
  std::mt19937_64 rng(61);
  int fallbacks = 0, trials = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    RandomContact c = random_contact(rng, trial % 2 == 0);
    const Vec3 t1 = c.n.unitOrthogonal(), t2 = c.n.cross(t1);
    Eigen::Matrix2d A;
    A << t1.dot(c.K * t1), t1.dot(c.K * t2), t2.dot(c.K * t1), t2.dot(c.K * t2);
    const Vec2 kn(t1.dot(c.K * c.n), t2.dot(c.K * c.n));
    const Vec2 stick = -(A.inverse() * kn);
    if (!(stick.norm() > 1e-3)) continue;
    c.mu = stick.norm() * (1 - std::pow(10.0, test::uniform(rng, -8, -4)));
    c.e = trial % 3 == 0 ? 1.0 : test::uniform(rng, 0, 1);
    const Vec2 ray = strike::restart_direction(kn, A, c.mu, stick);
    const double vn = c.v_rel.dot(c.n), slip = -vn * std::pow(10.0, test::uniform(rng, -5, -3));
    c.v_rel = vn * c.n + slip * (ray.x() * t1 + ray.y() * t2);
    const auto sol = strike::solve_impulse_energetic(c.K, c.v_rel, c.n, c.e, c.mu);
    ++trials;
    fallbacks += sol.step_cap_fallback;
    const double incoming = 0.5 * c.v_rel.dot(c.K.ldlt().solve(c.v_rel));
    CHECK(sol.energy_change <= 1e-9 * incoming);
    CHECK(std::isfinite(sol.impulse.norm()));
    CHECK(sol.impulse.dot(c.n) > 0);
  }
  INFO(fallbacks << " of " << trials << " took the legacy law at the step cap");
  CHECK(fallbacks == 0);
}

TEST_CASE("impulse (Stronge's energetic law): at e = 1 and within 1e-7 of it, friction's slips stopping and restarting create no energy", "[strike][physics]") {
  // At e = 1 only friction dissipates, and a slip that stops, sticks or restarts dissipates
  // little: any slip discarded without its impulse, or a work estimate off by its error term,
  // shows here as energy created. Checked to round-off (1e-12 of the incoming energy).
  std::mt19937_64 rng(47);
  double worst = -HUGE_VAL;
  for (int trial = 0; trial < 20000; ++trial) {
    RandomContact c = random_contact(rng, trial % 2 == 0);
    c.e = trial % 3 == 0 ? 1.0 : 1.0 - test::uniform(rng, 0, 1e-7);
    // Slips of every size against the normal approach: large, about the stopping one, tiny.
    const Vec3 slip0 = c.v_rel - c.v_rel.dot(c.n) * c.n;
    const double vn = c.v_rel.dot(c.n);
    const double size = std::pow(10.0, test::uniform(rng, -6, 1)) * c.mu * -vn;
    if (slip0.norm() > 0) c.v_rel = vn * c.n + size * slip0.normalized();
    const auto sol = strike::solve_impulse_energetic(c.K, c.v_rel, c.n, c.e, c.mu);
    const double incoming = 0.5 * c.v_rel.dot(c.K.ldlt().solve(c.v_rel));
    worst = std::max(worst, sol.energy_change / incoming);
    CHECK(sol.energy_change <= 1e-12 * incoming);
  }
  INFO("worst energy change, share of the incoming: " << worst);
  CHECK(worst <= 1e-12);
}

TEST_CASE("impulse (Stronge's energetic law): friction that would jam the restitution (Painleve's case) ends in a finite impulse", "[strike][physics]") {
  // Contacts whose friction, along the slip, would make the normal velocity fall as the normal
  // impulse grows (k_nn + k_n . f <= 0 for one slip direction): the law must end with a
  // finite, pushing, separating impulse and no energy created (the integration's step cap is
  // an invariant check: reaching it aborts).
  std::mt19937_64 rng(53);
  int jams = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const double m = 0.002;
    const Vec3 n = Vec3::UnitZ(), t1 = Vec3::UnitX();
    const double mu = test::uniform(rng, 0.5, 1.5);
    // A coupling k_nt so that mu k_nt exceeds k_nn along a slip along +t1.
    const double knn = 1 / m, knt = test::uniform(rng, 1.05, 3.0) * knn / mu;
    Eigen::Matrix3d K = Eigen::Matrix3d::Identity() * (knt * knt * m * 1.5 + 1 / m);
    K(2, 2) = knn * (1 + test::uniform(rng, 0, 0.5));
    K(0, 2) = K(2, 0) = knt * (test::uniform(rng, 0, 1) < 0.5 ? 1 : -1);
    REQUIRE(K.ldlt().isPositive());
    const Vec3 v_rel = -test::uniform(rng, 1, 30) * n + test::uniform(rng, -30, 30) * t1;
    const auto sol = strike::solve_impulse_energetic(K, v_rel, n, test::uniform(rng, 0, 1), mu);
    const double pn = sol.impulse.dot(n);
    jams += K(2, 2) - mu * std::abs(K(0, 2)) <= 0;
    REQUIRE(std::isfinite(pn));
    CHECK(pn > 0);
    CHECK(pn <= 4 * -v_rel.dot(n) / K(2, 2) * 10);
    const double incoming = 0.5 * v_rel.dot(K.ldlt().solve(v_rel));
    CHECK(sol.energy_change <= 1e-9 * incoming);
    const Vec3 after = v_rel + K * sol.impulse;
    CHECK(after.dot(n) >= -1e-9 * v_rel.norm());  // it separates
  }
  CHECK(jams > 1000);
}

TEST_CASE("impulse: frictionless and central, it is report 445-1's impact", "[strike][physics]") {
  const auto b = pivoted_blade();
  scenario::BladeGeometry g;
  g.edge.friction = 0;
  const strike::Spindle sp(b, g, blade::Restitution::constant(0.7));
  const auto nail = projectile::Projectile::capsule(0.0508, 0.00251, 0.002);
  strike::Contact k;
  k.edge = 0;
  k.radius = 0.55;
  k.radial = Vec3::UnitX(), k.forward = Vec3::UnitY();
  k.centre = {0.55, -0.003, sp.height};
  k.point = {0.55, -0.00125, sp.height};
  k.axis = Vec3::UnitZ();
  k.normal = Vec3::UnitY();
  const Vec3 v(0.0, -3.0, -2.5);
  const auto out = strike::strike(sp, k, nail, v, Vec3::Zero());
  REQUIRE(out.approaching);
  blade::StruckObject body;
  body.mass = nail.mass;
  body.velocity = v;
  const blade::BladeModel model(b);
  const auto report = blade::solve_impact(model, *blade::locate(b, 0, 0.55), body, blade::Restitution::constant(0.7));
  CHECK(out.velocity_after.y() == Approx(report.contact.velocity_after.y()).epsilon(1e-12));
  CHECK(out.velocity_after.z() == Approx(-2.5).epsilon(1e-12));
  CHECK(out.spin_after.norm() < 1e-9);
  CHECK(out.blade_effective_mass == Approx(report.blade_effective_mass).epsilon(1e-12));
}

TEST_CASE("impulse: angular momentum about the spindle and each pivot is conserved", "[strike][physics]") {
  const auto b = pivoted_blade();
  const blade::BladeModel model(b);
  std::mt19937_64 rng(23);
  const auto u = [&](double lo, double hi) { return test::uniform(rng, lo, hi); };
  int pushed = 0;
  for (int trial = 0; trial < 500; ++trial) {
    scenario::BladeGeometry g;
    g.edge.friction = u(0, 1);
    const strike::Spindle sp(b, g, blade::Restitution::constant(u(0, 1)));
    const auto nail = projectile::Projectile::capsule(0.0508, 0.00251, 0.002);
    strike::Contact k;
    k.edge = 0;
    k.radius = u(0.05, 0.6);
    k.forward_offset = -u(0, 0.05);  // on the plate, behind the edge line
    k.radial = Vec3::UnitX(), k.forward = Vec3::UnitY();
    k.axis = Vec3(u(-1, 1), u(-1, 1), u(-1, 1)).normalized();
    k.point = {k.radius, k.forward_offset, sp.height + u(-0.003, 0.003)};
    k.normal = Vec3(u(0.2, 1), u(-0.3, 0.3), u(-1, 1)).normalized();
    k.normal = Vec3(k.normal.y(), k.normal.x(), k.normal.z());  // mostly along the blade's motion (+y)
    k.centre = k.point + nail.radius() * k.normal + u(-0.02, 0.02) * k.axis;
    const Vec3 v(u(-20, 20), u(-20, 20), u(-5, 5));
    Vec3 w(u(-2000, 2000), u(-2000, 2000), u(-2000, 2000));
    w -= w.dot(k.axis) * k.axis;
    const auto out = strike::strike(sp, k, nail, v, w);
    if (!out.approaching) continue;
    const Vec3& P = out.solution.impulse;
    // The impact alone (velocity_after, spin_after; the driven blade's push after it is the
    // motor's, tested below).
    const Eigen::Matrix3d inertia = strike::inverse_inertia(nail, k.axis).inverse();
    const Vec3 r = k.point - k.centre;
    const Vec3& v_after = out.velocity_after;
    const Vec3& w_after = out.spin_after;
    pushed += out.push.norm() > 0;
    // The nail: linear and angular momentum change by the impulse and its moment.
    CHECK((nail.mass * (v_after - v) - P).norm() < 1e-12);
    CHECK((inertia * (w_after - w) - r.cross(P)).norm() < 1e-9 * (1 + P.norm()));
    // With the push, the nail's point does not approach the rigid blade's.
    CHECK((out.pushed_velocity() + out.pushed_spin().cross(r) - sp.velocity_at(k.point)).dot(k.normal) >= -1e-6);
    // The blade takes -P at the contact: its generalised momenta change by the moments of -P
    // about the spindle (all coordinates together) and about the pivot (the link's own).
    const auto where = *blade::locate(b, 0, k.radius);
    const Eigen::VectorXd dq = model.rates_after(where, k.forward_offset, -P.dot(k.forward), -P.dot(k.radial)) - model.rigid_rates();
    const Eigen::VectorXd dp = model.mass_matrix() * dq;
    const Vec3 nail_about_spindle = k.point.cross(P);  // the spindle's axis through the origin
    CHECK(dp.sum() + nail_about_spindle.z() == Approx(0).margin(1e-9));
    if (!where.on_hub) {
      const Vec3 pin(0.3048, 0.0, k.point.z());
      CHECK(dp[1] + (k.point - pin).cross(P).z() == Approx(0).margin(1e-9));  // coordinate 1: arm 0's link
    }
    // And the energy of nail and blade together does not grow.
    const double nail_before = 0.5 * nail.mass * v.squaredNorm() + 0.5 * w.dot(inertia * w);
    const double nail_after = 0.5 * nail.mass * v_after.squaredNorm() + 0.5 * w_after.dot(inertia * w_after);
    const double blade_before = model.kinetic_energy(model.rigid_rates()), blade_after = model.kinetic_energy(model.rigid_rates() + dq);
    CHECK(nail_after + blade_after <= nail_before + blade_before + 1e-9 * (nail_before + blade_before));
  }
  INFO("trials where the rigid blade pushed after the impact: " << pushed);
  CHECK(pushed <= 5);  // a 2 g nail against 2.5 kg links: only at restitutions near 0
}

TEST_CASE("strike: a heavy stone that still approaches the yielded pivoted blade is carried on by the driven blade", "[strike][physics]") {
  // A 1.27 kg cobble struck by a pivoted blade's link (2.5 kg): the link yields so much that,
  // the blade turning rigidly again, the stone's point still approaches it. Frictionless, the
  // push leaves it moving with the rigid blade's point along the normal, its tangential
  // velocity and spin untouched (a hand calculation, not the solver's): the sum of the impacts
  // a rigid-blade search would otherwise find one after another at that instant.
  const auto b = pivoted_blade();
  for (const double friction : {0.0, 0.4}) {
    scenario::BladeGeometry g;
    g.edge.friction = friction;
    const strike::Spindle sp(b, g, blade::Restitution::constant(0.475));
    const auto stone = projectile::Projectile::sphere(0.0971, 1.2718);
    strike::Contact k;
    k.edge = 0;
    k.radius = 0.55;
    k.radial = Vec3::UnitX(), k.forward = Vec3::UnitY();
    k.normal = Vec3(0.1, 0.9, -0.4).normalized();
    k.point = {0.55, 0.0, sp.height};
    k.centre = k.point + stone.radius() * k.normal;
    k.axis = Vec3::UnitZ();
    const Vec3 v(2.0, -1.0, -0.5), w(5.0, -3.0, 20.0);
    const auto out = strike::strike(sp, k, stone, v, w);
    REQUIRE(out.approaching);
    const Vec3 u = sp.velocity_at(k.point);
    const Vec3 r = k.point - k.centre;
    // The impact alone leaves the stone's point approaching the rigid blade's.
    CHECK((out.velocity_after - u).dot(k.normal) < -1.0);  // m/s: why the push is there at all
    CHECK(out.push.dot(k.normal) > 0);
    CHECK((out.push_velocity - out.push / stone.mass).norm() < 1e-12);
    const Vec3 v_push = out.pushed_velocity(), w_push = out.pushed_spin();
    // After it, the point neither approaches nor parts: a plastic push, within round-off.
    const double left = (v_push + w_push.cross(r) - u).dot(k.normal);
    CHECK(left == Approx(0).margin(1e-9));
    if (friction == 0.0) {
      CHECK((v_push - (out.velocity_after + (u - out.velocity_after).dot(k.normal) * k.normal)).norm() < 1e-9);  // a plastic impact on an immovable blade
      CHECK((w_push - out.spin_after).norm() < 1e-9);  // a ball's normal passes through its centre
    } else {
      CHECK(out.push.dot(k.normal) * friction >= (out.push - out.push.dot(k.normal) * k.normal).norm() - 1e-12);  // inside the cone
    }
  }
}

TEST_CASE("contact search: agrees with the fixed-step reference, and leaves no overlap after a strike", "[strike][search][long]") {
  auto s = bar_scenario();
  s.spindles[0].geometry.edge.sail_height = 0.02;  // plate, bevel and sail all in play
  const auto sp = spindle(s);
  int struck = 0, matched = 0, restruck = 0, rematched = 0;
  for (int i = 0; i < 150; ++i) {
    random::Stream rng(31, 0, static_cast<std::uint64_t>(i), random::Purpose::Feed);
    const auto drop = feed::sample_drop(s, i, rng);
    const auto fall = feed::fall_through(drop, sp);
    strike::SearchStats stats, ref_stats;
    const auto c = strike::first_contact(sp, drop.blade_phase, drop.nail, fall.motion, fall.until, stats);
    const auto r = strike::first_contact(sp, drop.blade_phase, drop.nail, fall.motion, fall.until, ref_stats, strike::SearchMethod::FixedSteps);
    if (c.has_value() != r.has_value()) {
      const auto& k = c ? *c : *r;
      FAIL_CHECK("nail " << i << ": only the " << (c ? "search" : "reference") << " finds a touch, at t = " << k.time << ", edge " << k.edge
                         << ", normal (" << k.normal.transpose() << "), offset " << k.forward_offset << ", radius " << k.radius);
      continue;
    }
    if (!c) continue;
    ++struck;
    // Both stop within the contact tolerance of the touch: the same time to within that
    // tolerance over the approach speed.
    const auto first = strike::strike(sp, *c, drop.nail, fall.motion.velocity(c->time), Vec3::Zero());
    const double slack = std::max(1e-6, 2 * strike::kContactTolerance / first.approach_speed);
    const bool same = c->edge == r->edge && std::abs(c->time - r->time) < slack;
    if (!same)
      FAIL_CHECK("nail " << i << ": search t = " << c->time << " edge " << c->edge << " (" << c->normal.transpose() << "), reference t = " << r->time
                         << " edge " << r->edge << " (" << r->normal.transpose() << ")");
    matched += same;
    // After the strike: the next touch the search finds, and no overlap before it.
    const auto out = strike::strike(sp, *c, drop.nail, fall.motion.velocity(c->time), Vec3::Zero());
    REQUIRE(out.approaching);
    strike::Motion after;
    after.p0 = c->centre, after.v0 = out.velocity_after, after.a = fall.motion.a, after.t0 = c->time, after.axis0 = c->axis;
    after.spin = out.spin_after - out.spin_after.dot(c->axis) * c->axis;
    const double until = c->time + 0.002;
    const auto next = strike::first_contact(sp, drop.blade_phase, drop.nail, after, until, stats);
    const auto next_ref = strike::first_contact(sp, drop.blade_phase, drop.nail, after, until, ref_stats, strike::SearchMethod::FixedSteps);
    restruck += next.has_value();
    rematched += next.has_value() == next_ref.has_value() && (!next || std::abs(next->time - next_ref->time) < 1e-5);
    const double end = next ? next->time : until;
    double worst = HUGE_VAL;
    for (double t = c->time + 1e-7; t < end; t += 2e-7)
      for (std::size_t e = 0; e < sp.edges.size(); ++e) {
        const auto gap = strike::clearance(sp, e, drop.blade_phase, drop.nail, after, t);
        if (!gap.off_arm) worst = std::min(worst, gap.distance);
      }
    CHECK(worst >= -1e-5);
  }
  CHECK(struck > 60);
  CHECK(matched == struck);
  CHECK(restruck > 10);
  CHECK(rematched >= restruck - 1);
}

TEST_CASE("feed: strike probability and strike time match the blade's sweep", "[strike][feed][statistics]") {
  // Two edges 180 deg apart sweep a given azimuth every pi / omega, each plate taking
  // tau = (width + diameter) / (omega r) to pass. An upright nail spans the plate's height
  // for a window W (from its tip at the top face to its head past the bottom one); it is
  // struck if a plate is under it at any time in [-tau, W] (from -tau it lands on the
  // plate's top face as its tip reaches it, at time 0): with probability (W + tau) omega / pi,
  // and the edge's strikes come at a time uniform on [0, W].
  auto s = bar_scenario();
  s.feed.outlet_speed_max = 0;  // fixed fall speed: a fixed window
  s.feed.tilt_max = 0;
  s.feed.outlet_diameter = 1e-6;  // at one radius
  s.nail.length_tolerance = 0;
  s.spindles[0].geometry.edge.bevel_angle = 90 * units::degree;
  const auto sp = spindle(s);
  REQUIRE(sp.edges.size() == 2);
  std::vector<double> edge_times;
  const int n = 6000;
  int struck = 0, landed = 0;
  double window = 0;
  const double omega = s.spindles[0].blade.omega, tau = (sp.section.shape().width + s.nail.diameter) / (omega * 0.55);
  for (int i = 0; i < n; ++i) {
    random::Stream rng(11, 0, static_cast<std::uint64_t>(i), random::Purpose::Feed);
    const auto d = feed::sample_drop(s, i, rng);
    const double v = d.fall_speed, depth = sp.section.shape().thickness + d.nail.length;
    window = (-v + std::sqrt(v * v + 2 * feed::kGravity * depth)) / feed::kGravity;
    const auto fall = feed::fall_through(d, sp);
    strike::SearchStats stats;
    const auto c = strike::first_contact(sp, d.blade_phase, d.nail, fall.motion, fall.until, stats);
    if (!c) continue;
    ++struck;
    if (c->normal.z() > 0.999) {
      ++landed;
      CHECK(std::abs(c->time) < 1e-5);
    } else {
      edge_times.push_back(c->time);
    }
  }
  const double p = (window + tau) * omega / units::pi;
  const double se = std::sqrt(p * (1 - p) / n);
  CHECK(std::abs(static_cast<double>(struck) / n - p) < 4 * se);
  const double p_land = tau * omega / units::pi;
  CHECK(std::abs(static_cast<double>(landed) / n - p_land) < 4 * std::sqrt(p_land * (1 - p_land) / n));
  CHECK(test::ks_statistic(edge_times, [&](double t) { return t / window; }) < test::ks_critical_001(edge_times.size()));
}

TEST_CASE("feed: nails outside the tip circle fall through", "[strike][feed]") {
  auto s = bar_scenario();
  s.feed.stations = std::vector<scenario::FeedStation>{{0, 0.70, 0.5}};  // beyond the 0.6096 m reach
  const auto sp = spindle(s);
  int struck = 0;
  for (int i = 0; i < 500; ++i) {
    random::Stream rng(3, 0, static_cast<std::uint64_t>(i), random::Purpose::Feed);
    const auto d = feed::sample_drop(s, i, rng);
    const auto fall = feed::fall_through(d, sp);
    strike::SearchStats stats;
    struck += strike::first_contact(sp, d.blade_phase, d.nail, fall.motion, fall.until, stats).has_value();
  }
  CHECK(struck == 0);
}

TEST_CASE("contact search: nails crossing the tip circle, spinning, agree with the reference", "[strike][search]") {
  // Across the tip radius the search clips the core to the arm and meets its end face; a
  // core partly beyond the tip bounds its steps by its distance from the wedge behind the
  // section's separating line and the tip's plane.
  auto s = bar_scenario();
  const auto sp = spindle(s);
  const auto nail = projectile::Projectile::capsule(0.0508, 0.00251, 0.002);
  std::mt19937_64 rng(41);
  const auto u = [&](double lo, double hi) { return test::uniform(rng, lo, hi); };
  int found = 0, agree = 0, total = 0;
  for (int i = 0; i < 120; ++i) {
    strike::Motion m;
    const double r = sp.reach + u(-0.03, 0.04), az = u(0, 2 * units::pi);
    m.p0 = {r * std::cos(az), r * std::sin(az), sp.height + u(-0.01, 0.01)};
    const Vec3 radial(std::cos(az), std::sin(az), 0);
    m.v0 = u(-20, 10) * radial + Vec3(u(-5, 5), u(-5, 5), u(-2, 2));
    m.a = {0, 0, -feed::kGravity};
    m.axis0 = Vec3(u(-1, 1), u(-1, 1), u(-0.5, 0.5)).normalized();
    m.spin = Vec3(u(-2000, 2000), u(-2000, 2000), u(-2000, 2000));
    m.spin -= m.spin.dot(m.axis0) * m.axis0;
    const double phase = u(0, 2 * units::pi);
    strike::SearchStats stats;
    const auto c = strike::first_contact(sp, phase, nail, m, 0.02, stats);
    const auto ref = strike::first_contact(sp, phase, nail, m, 0.02, stats, strike::SearchMethod::FixedSteps);
    ++total;
    found += ref.has_value();
    const bool same = c.has_value() == ref.has_value() && (!c || (c->edge == ref->edge && std::abs(c->time - ref->time) < 2e-6));
    if (!same)
      WARN("motion " << i << ": search " << (c ? c->time : -1.0) << ", reference " << (ref ? ref->time : -1.0));
    agree += same;
  }
  CHECK(found > 30);
  CHECK(agree >= total - 2);  // a grazing touch within the search's 0.2 mm floor may differ
}

TEST_CASE("contact search: a stone turning with the arm just ahead of it is searched to its end, as the reference finds", "[strike][search]") {
  // A cobble the knife has just pushed moves on at the knife's speed just ahead of it: the
  // arm closes on the window about it far slower than its bound on the arm's rate, so the
  // window's steps shrink geometrically. On the shipped chained shoulder such a search ran to
  // its step cap and cut the stone off (object 4991); the exact distance's bound now carries
  // it on. Stones of 60-100 mm at the blade's height, just beyond the search's window ahead
  // of an arm (by 1e-7 to 1e-3 rad past its half-angle, the bound the search draws it with),
  // moving along the arm's direction at 97-100 % of its speed there, give the reference's
  // answer.
  const auto s = bar_scenario();
  const auto sp = spindle(s);
  std::mt19937_64 rng(97);
  const auto u = [&](double lo, double hi) { return test::uniform(rng, lo, hi); };
  int agree = 0, total = 0, found = 0;
  for (int i = 0; i < 60; ++i) {
    const double d = u(0.06, 0.1);
    const auto stone = projectile::Projectile::sphere(d, 2650 * units::pi / 6 * d * d * d);
    const double r = u(0.25, sp.reach - 0.02), phase = u(0, 2 * units::pi);
    const double ahead = search_window(0.5 * d, r) + std::pow(10.0, u(-7, -3));
    const double az = phase + sp.edges[0].azimuth + sp.sense * ahead;  // (at t = 0, as the search measures it)
    const Vec3 radial(std::cos(az), std::sin(az), 0), along = sp.sense * Vec3::UnitZ().cross(radial);
    strike::Motion m;
    m.p0 = Vec3(sp.centre.x(), sp.centre.y(), 0) + r * radial + Vec3(0, 0, sp.height + u(-0.01, 0.01));
    m.v0 = sp.omega() * r * u(0.97, 1.0) * along + u(-2, 2) * radial;
    m.a = {0, 0, -feed::kGravity};
    m.axis0 = Vec3::UnitZ();
    strike::SearchStats stats, ref_stats;
    const auto c = strike::first_contact(sp, phase, stone, m, 0.01, stats);
    const auto ref = strike::first_contact(sp, phase, stone, m, 0.01, ref_stats, strike::SearchMethod::FixedSteps);
    INFO("stone " << i << ": search " << (c ? c->time : -1.0) << ", reference " << (ref ? ref->time : -1.0) << ", steps " << stats.steps);
    CHECK_FALSE(stats.gave_up);
    ++total;
    found += ref.has_value();
    agree += c.has_value() == ref.has_value() && (!c || (c->edge == ref->edge && std::abs(c->time - ref->time) < 2e-6));
  }
  CHECK(found > 5);
  CHECK(agree >= total - 2);
}

TEST_CASE("contact search: a body just beyond the tip, turning with the arm or passing along the tip circle, is searched to its end", "[strike][search]") {
  // The search's window stalls in two more ways, each with the probe finding the body wholly
  // beyond the tip, where the exact distance's step is not taken but the off-arm one is:
  // (1) a stone just struck, flying on at the knife tip's speed just beyond the tip and just
  // ahead of the window (the chained shoulder's object 49763 was cut off so); (2) a nail
  // passing the tip circle almost along it, its radial gap closing far slower than its whole
  // speed, the bound's rate (the front-mount deck's replicate 1413, nail 21). Each search
  // must run to its end and give the fixed-step reference's answer. These bodies fly clear
  // (a body flying on beyond the tip is not caught again), so the answer checked is "none"
  // and what fails without the fix is the search giving up (12 of these 80). (A level nail
  // whose end reaches the tip's face by 1e-8 to 1e-6 m, less than the touch tolerance, is
  // found by the reference and not by the search, with or without the fix: a graze below
  // the search's floor, docs/model.md §5.1b.)
  const auto s = bar_scenario();
  const auto sp = spindle(s);
  std::mt19937_64 rng(149);
  const auto u = [&](double lo, double hi) { return test::uniform(rng, lo, hi); };
  int agree = 0, total = 0;
  for (int i = 0; i < 80; ++i) {
    const bool along_tip = i % 2 == 1;
    const auto body = along_tip ? projectile::Projectile::capsule(0.051, 0.0029, 0.0027)
                                : projectile::Projectile::sphere(u(0.02, 0.04), 0.03);
    const double rho = body.half_segment() + body.radius(), phase = u(0, 2 * units::pi);
    strike::Motion m;
    m.a = {0, 0, -feed::kGravity};
    m.axis0 = Vec3(u(-0.1, 0.1), u(-0.1, 0.1), 1).normalized();
    if (!along_tip) {
      // Its centre beyond the tip by less than its radius (within the tip circle's reach, as
      // the window's radial bound sees it), 1e-7 to 1e-3 rad ahead of the window, at 97-103 %
      // of the tip's speed there along the arm's direction.
      const double r = sp.reach + u(1e-4, rho);
      const double az = phase + sp.edges[0].azimuth + sp.sense * (search_window(rho, r) + std::pow(10.0, u(-7, -3)));
      const Vec3 radial(std::cos(az), std::sin(az), 0), along = sp.sense * Vec3::UnitZ().cross(radial);
      m.p0 = Vec3(sp.centre.x(), sp.centre.y(), sp.height + u(-0.005, 0.005)) + r * radial;
      m.v0 = sp.omega() * r * u(0.97, 1.03) * along;
    } else {
      // Straight along a line whose nearest point to the axis is 1e-7 to 1e-4 m beyond the
      // reach plus the nail's, that point a few microseconds ahead, at 5-20 m/s, inside the
      // arm's window (at its azimuth, the arm just behind it).
      const double r_min = sp.reach + rho + std::pow(10.0, u(-7, -4)), speed = u(5, 20);
      const double az = phase + sp.edges[0].azimuth + sp.sense * u(0.0, 0.02);
      const Vec3 radial(std::cos(az), std::sin(az), 0), along = (u(0, 1) < 0.5 ? 1.0 : -1.0) * Vec3::UnitZ().cross(radial);
      m.p0 = Vec3(sp.centre.x(), sp.centre.y(), sp.height + u(-0.005, 0.005)) + r_min * radial - speed * u(1e-6, 1e-4) * along;
      m.v0 = speed * along;
      m.a = Vec3::Zero();  // (a straight line: its nearest approach is where it was put)
    }
    strike::SearchStats stats, ref_stats;
    const auto c = strike::first_contact(sp, phase, body, m, 0.01, stats);
    const auto ref = strike::first_contact(sp, phase, body, m, 0.01, ref_stats, strike::SearchMethod::FixedSteps);
    INFO((along_tip ? "nail " : "stone ") << i << ": search " << (c ? c->time : -1.0) << ", reference " << (ref ? ref->time : -1.0)
                                          << ", steps " << stats.steps);
    CHECK_FALSE(stats.gave_up);
    ++total;
    agree += c.has_value() == ref.has_value() && (!c || (c->edge == ref->edge && std::abs(c->time - ref->time) < 2e-6));
  }
  CHECK(agree >= total - 2);
}
