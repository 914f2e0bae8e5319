// Invariants of the impact core over many random blades (docs/model.md §2–3):
// angular momentum about the spindle and about every pivot, restitution at the
// contact, energy loss >= 0 (zero at e = 1), the heavy-blade limit and seized pins.
#include <catch2/catch.hpp>
#include <cmath>

#include "blade/blade_model.hpp"
#include "blade/impact.hpp"
#include "physics_check.hpp"
#include "random_blades.hpp"

using namespace j232;
using namespace j232::test;

namespace {

blade::StruckObject point_object(double mass, blade::Vec3 velocity) {
  blade::StruckObject o;
  o.mass = mass;
  o.velocity = velocity;
  return o;
}

blade::Link uniform_link(double length, double mass) {
  blade::Link l;
  l.length = length;
  l.mass = mass;
  return l;
}

struct Trial {
  blade::Blade blade;
  blade::ContactLocation where;
  blade::StruckObject object;
  blade::Restitution restitution;
  blade::ImpactSolution solution;
  double radius = 0.0;
};

// Draws until the object is approaching the contact (a few draws at most).
Trial draw(std::mt19937_64& rng, const RandomBladeOptions& options, bool eccentric, double e) {
  for (;;) {
    Trial t;
    t.blade = random_blade(rng, options);
    t.where = random_contact(rng, t.blade);
    t.object = random_object(rng, eccentric);
    t.restitution = e < 0 ? blade::Restitution::power_law(1.06, -0.25, 0.9) : blade::Restitution::constant(e);
    t.radius = blade::contact_radius(t.blade, t.where);
    if (t.radius < 1e-3) continue;
    const blade::BladeModel model(t.blade);
    try {
      t.solution = blade::solve_impact(model, t.where, t.object, t.restitution);
    } catch (const std::invalid_argument&) {
      continue;  // not approaching: draw again
    }
    return t;
  }
}

ObjectState before(const Trial& t) { return {t.object.velocity, t.object.spin}; }
ObjectState after(const Trial& t) { return {t.solution.contact.velocity_after, t.solution.contact.spin_after}; }

// Every free pivot of every arm: the links outboard of it, plus the object if it struck there.
void check_pivot_momenta(const Trial& t) {
  const BladeRates r0 = rigid(t.blade), r1 = j232::test::after(t.solution);
  for (std::size_t a = 0; a < t.blade.arms.size(); ++a)
    for (std::size_t k = 0; k < t.blade.arms[a].links.size(); ++k) {
      if (t.blade.arms[a].links[k].seized) continue;  // a seized pin carries moment: no conservation law there
      const double rho = t.blade.arms[a].pin_radius(k);
      const bool object_outboard = !t.where.on_hub && t.where.arm == a && t.where.link >= k;
      double h0 = arm_momentum(t.blade, r0, a, k, rho), h1 = arm_momentum(t.blade, r1, a, k, rho);
      if (object_outboard) {
        h0 += object_momentum(t.object, t.radius, before(t), rho);
        h1 += object_momentum(t.object, t.radius, after(t), rho);
      }
      const double scale = std::abs(h0) + t.solution.contact.impulse * t.radius + 1e-12;
      INFO("arm " << a + 1 << " pivot " << k + 1 << " (" << t.blade.arms[a].links.size() << " links)");
      CHECK(std::abs(h1 - h0) <= 1e-9 * scale);
    }
}

void check_restitution(const Trial& t) {
  const BladeRates r1 = j232::test::after(t.solution);
  const double blade_after = point_speed(t.blade, r1, t.where);
  blade::Vec3 arm = blade::Vec3::Zero();
  if (t.object.rod) arm = t.object.rod->offset * t.object.rod->axis;
  const double object_after = (t.solution.contact.velocity_after + t.solution.contact.spin_after.cross(arm)).y();
  const double separation = object_after - blade_after;
  CHECK(separation == Approx(t.solution.contact.e * t.solution.contact.approach_speed).epsilon(1e-9).margin(1e-12));
}

}  // namespace

TEST_CASE("impact: angular momentum about the spindle and every pivot is conserved", "[impact][property]") {
  std::mt19937_64 rng(20261121);
  for (int i = 0; i < 400; ++i) {
    const bool eccentric = i % 2 == 1;
    const Trial t = draw(rng, {.constant_speed_hub = false, .seized_probability = i % 3 == 0 ? 0.25 : 0.0}, eccentric,
                         i % 4 == 0 ? -1.0 : 0.9 * (i % 7) / 6.0);
    const BladeRates r0 = rigid(t.blade), r1 = j232::test::after(t.solution);
    const double h0 = blade_momentum_about_spindle(t.blade, r0) + object_momentum(t.object, t.radius, before(t), 0.0);
    const double h1 = blade_momentum_about_spindle(t.blade, r1) + object_momentum(t.object, t.radius, after(t), 0.0);
    INFO("trial " << i << ", arms " << t.blade.arms.size());
    CHECK(std::abs(h1 - h0) <= 1e-9 * (std::abs(h0) + t.solution.contact.impulse * t.radius));
    check_pivot_momenta(t);
    check_restitution(t);
  }
}

TEST_CASE("impact: pivots conserve momentum with a constant-speed hub too", "[impact][property]") {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 200; ++i) {
    const Trial t = draw(rng, {.constant_speed_hub = true, .seized_probability = 0.2}, i % 2 == 0, 0.7);
    INFO("trial " << i);
    CHECK(t.solution.hub_rate_after == t.blade.omega);
    check_pivot_momenta(t);
    check_restitution(t);
  }
}

TEST_CASE("impact: energy lost is >= 0, matches the bodies' energies, and is zero at e = 1", "[impact][property]") {
  std::mt19937_64 rng(99);
  for (int i = 0; i < 300; ++i) {
    const double e = (i % 3 == 0) ? 1.0 : (i % 3 == 1 ? 0.0 : 0.45);
    const Trial t = draw(rng, {.seized_probability = 0.2}, i % 2 == 0, e);
    const BladeRates r0 = rigid(t.blade), r1 = j232::test::after(t.solution);
    const double t0 = blade_energy(t.blade, r0) + object_energy(t.object, before(t));
    const double t1 = blade_energy(t.blade, r1) + object_energy(t.object, after(t));
    INFO("trial " << i << ", e = " << e);
    CHECK(t.solution.contact.energy_lost >= 0.0);
    CHECK(t0 - t1 == Approx(t.solution.contact.energy_lost).margin(1e-9 * t0));
    if (e == 1.0) CHECK(std::abs(t0 - t1) <= 1e-9 * t0);
    // The model's own energy bookkeeping (mass matrix) agrees with the bodies'.
    CHECK(t.solution.blade_energy_before == Approx(blade_energy(t.blade, r0)).epsilon(1e-10));
  }
}

TEST_CASE("impact: Case III chains of N = 1..8 links conserve momentum about every pivot", "[impact][property]") {
  for (int n = 1; n <= 8; ++n) {
    Trial t;
    t.blade.omega = 104.72;
    t.blade.hub = {.bar_mass = 1.0, .bar_length = 0.1, .bar_mount = blade::BarMount::End};
    blade::Arm arm{0.0, 0.1, {}};
    for (int k = 0; k < n; ++k) arm.links.push_back(uniform_link(0.5 / n, 9.0 / n));
    t.blade.arms = {arm};
    t.where = blade::ContactLocation::on_link(0, static_cast<std::size_t>(n - 1), 0.9 * 0.5 / n);
    t.radius = blade::contact_radius(t.blade, t.where);
    t.object.mass = 0.002;
    t.object.velocity = {0.0, -2.2352, 0.0};
    t.restitution = blade::Restitution::constant(0.9);
    t.solution = blade::solve_impact(blade::BladeModel(t.blade), t.where, t.object, t.restitution);
    INFO("N = " << n);
    check_pivot_momenta(t);
    check_restitution(t);
    // More pins outboard make the tip lighter: the nail cannot leave faster than (1 + e) v_p + e v_c.
    CHECK(t.solution.contact.velocity_after.y() < 1.9 * t.blade.omega * t.radius + 0.9 * 2.2352);
  }
}

TEST_CASE("impact: a heavy blade throws the object at (1 + e) v_p + e v_c", "[impact][property]") {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 100; ++i) {
    blade::Blade b = random_blade(rng, {.seized_probability = 0.2});
    const double factor = 1e9;  // every mass and inertia a billion times heavier
    b.hub.bar_mass *= factor;
    b.hub.extra_inertia *= factor;
    b.hub.drive_inertia *= factor;
    for (auto& arm : b.arms)
      for (auto& l : arm.links) {
        l.mass *= factor;
        if (l.inertia_about_centre) *l.inertia_about_centre *= factor;
      }
    const auto where = random_contact(rng, b);
    const double vp = b.omega * blade::contact_radius(b, where);
    const double vc = 2.2352, e = 0.3 + 0.6 * (i % 4) / 3.0;
    blade::StruckObject o = point_object(0.002, {0.0, -vc, 0.0});
    const auto s = blade::solve_impact(blade::BladeModel(b), where, o, blade::Restitution::constant(e));
    CHECK(s.contact.velocity_after.y() == Approx((1 + e) * vp + e * vc).epsilon(1e-6));
  }
  // The limit itself: a constant-speed hub struck on its own bar is immovable.
  blade::Blade b;
  b.omega = 100.0;
  b.hub = {.bar_mass = 1.0, .bar_length = 0.6, .bar_mount = blade::BarMount::End, .constant_speed = true};
  const blade::BladeModel model(b);
  CHECK(std::isinf(model.effective_mass(blade::ContactLocation::hub(0.5))));
  blade::StruckObject o = point_object(0.002, {0.0, -2.0, 0.0});
  const auto s = blade::solve_impact(model, blade::ContactLocation::hub(0.5), o, blade::Restitution::constant(0.8));
  CHECK(s.contact.velocity_after.y() == Approx(1.8 * 50.0 + 0.8 * 2.0).epsilon(1e-14));
}

TEST_CASE("impact: a blade whose pivots are all seized is the straight blade of the same mass distribution", "[impact][property]") {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 100; ++i) {
    blade::Blade b = random_blade(rng, {.seized_probability = 1.0});
    const auto where = random_contact(rng, b);
    const double radius = blade::contact_radius(b, where);
    if (radius < 1e-3) continue;
    // The straight blade: one rigid body whose inertia about the spindle is the sum of the parts'.
    blade::Blade straight;
    straight.omega = b.omega;
    straight.hub.extra_inertia = blade_momentum_about_spindle(b, rigid(b)) / b.omega;
    const blade::BladeModel pinned(b), rigid_blade(straight);
    blade::StruckObject o = point_object(0.05, {0.3, -2.0, 0.1});
    const auto s1 = blade::solve_impact(pinned, where, o, blade::Restitution::constant(0.6));
    const auto s2 = blade::solve_impact(rigid_blade, blade::ContactLocation::hub(radius), o, blade::Restitution::constant(0.6));
    INFO("trial " << i);
    CHECK(s1.blade_effective_mass == Approx(s2.blade_effective_mass).epsilon(1e-10));
    CHECK(s1.contact.velocity_after.y() == Approx(s2.contact.velocity_after.y()).epsilon(1e-10));
    for (const auto& arm : s1.link_rates)
      for (double rate : arm) CHECK(rate == Approx(s1.hub_rate_after).epsilon(1e-10));
  }
}

TEST_CASE("impact: eccentric impact on a slender rod", "[impact][eccentric]") {
  blade::BladeAtContact at{.effective_mass = 4.0, .speed = 60.0, .normal = blade::Vec3::UnitY()};
  blade::StruckObject nail = point_object(0.002, {0.0, -2.0, 0.0});
  const auto central = blade::resolve_contact(at, nail, blade::Restitution::constant(0.5));

  SECTION("struck at its centre it behaves as a point mass") {
    nail.rod = blade::Rod{.length = 0.0508, .transverse_inertia = 0.002 * 0.0508 * 0.0508 / 12, .offset = 0.0};
    const auto c = blade::resolve_contact(at, nail, blade::Restitution::constant(0.5));
    CHECK(c.velocity_after.y() == Approx(central.velocity_after.y()).epsilon(1e-14));
    CHECK(c.spin_after.norm() == 0.0);
  }
  SECTION("struck at its end: effective mass m / 4 for a uniform rod, and it spins") {
    const double L = 0.0508;
    nail.rod = blade::Rod{.length = L, .transverse_inertia = 0.002 * L * L / 12, .offset = L / 2};
    const auto c = blade::resolve_contact(at, nail, blade::Restitution::constant(0.5));
    CHECK(c.object_effective_mass == Approx(0.002 / 4).epsilon(1e-12));
    CHECK(c.velocity_after.y() < central.velocity_after.y());
    // Spin about the radial axis: the top (contact) is pushed forward, the centre lags.
    CHECK(c.spin_after.x() == Approx(-c.impulse * (L / 2) / (0.002 * L * L / 12)).epsilon(1e-12));
    // Its contact point separates at e times the approach speed.
    const double point = (c.velocity_after + c.spin_after.cross(blade::Vec3(0, 0, L / 2))).y();
    CHECK(point - c.blade_speed_after == Approx(0.5 * c.approach_speed).epsilon(1e-12));
  }
}

TEST_CASE("impact: an object that outruns the blade is not struck", "[impact]") {
  blade::BladeAtContact at{.effective_mass = 4.0, .speed = 10.0, .normal = blade::Vec3::UnitY()};
  blade::StruckObject o = point_object(0.002, {0.0, 12.0, 0.0});
  const auto c = blade::resolve_contact(at, o, blade::Restitution::constant(0.5));
  CHECK_FALSE(c.approaching);
  CHECK(c.impulse == 0.0);
  CHECK(c.velocity_after == o.velocity);
}
