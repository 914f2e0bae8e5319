#pragma once
// Random blades, contacts and objects for property tests: every shape the impact core
// accepts (Case I, II, III up to 8 links, several arms, hub and drive inertia, seized
// pins, explicit link inertia and centre of mass, eccentric rods).
#include <cstdint>
#include <random>

#include "blade/blade.hpp"
#include "blade/impact.hpp"

namespace j232::test {

struct RandomBladeOptions {
  bool constant_speed_hub = false;
  double seized_probability = 0.0;
  int max_arms = 3;
  int max_links = 8;
};

// Drawn from the engine's raw 64-bit output by fixed formulas, not by std::
// distributions (whose algorithms each standard library chooses): the same blades on
// every compiler, as the program's own random streams are.
inline double uniform(std::mt19937_64& rng, double lo, double hi) {
  const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;  // [0, 1), 53 random bits
  return lo + (hi - lo) * u;
}
inline int integer(std::mt19937_64& rng, int lo, int hi) {
  const auto span = static_cast<std::uint64_t>(hi - lo) + 1;  // small: the modulo's bias is below 2^-58
  return lo + static_cast<int>(rng() % span);
}

inline blade::Blade random_blade(std::mt19937_64& rng, const RandomBladeOptions& o) {
  blade::Blade b;
  b.omega = uniform(rng, 30.0, 120.0);
  b.hub.bar_mount = integer(rng, 0, 1) ? blade::BarMount::End : blade::BarMount::Centre;
  b.hub.bar_length = uniform(rng, 0.1, 0.8);
  b.hub.bar_mass = uniform(rng, 0.2, 5.0);
  b.hub.extra_inertia = integer(rng, 0, 1) ? uniform(rng, 0.0, 0.05) : 0.0;
  b.hub.drive_inertia = integer(rng, 0, 1) ? uniform(rng, 0.0, 0.5) : 0.0;
  b.hub.constant_speed = o.constant_speed_hub;
  const int arms = integer(rng, o.max_arms > 0 ? 1 : 0, o.max_arms);
  for (int a = 0; a < arms; ++a) {
    blade::Arm arm;
    arm.azimuth = uniform(rng, 0.0, 6.283185307179586);
    arm.pivot_radius = integer(rng, 0, 2) ? b.hub.reach() : uniform(rng, 0.02, b.hub.reach());
    const int links = integer(rng, 1, o.max_links);
    for (int k = 0; k < links; ++k) {
      blade::Link l;
      l.length = uniform(rng, 0.02, 0.3);
      l.mass = uniform(rng, 0.05, 3.0);
      if (integer(rng, 0, 3) == 0) l.centre_of_mass = uniform(rng, 0.1, 0.9) * l.length;
      if (integer(rng, 0, 3) == 0) l.inertia_about_centre = uniform(rng, 0.2, 2.0) * l.mass * l.length * l.length / 12.0;
      l.seized = uniform(rng, 0.0, 1.0) < o.seized_probability;
      arm.links.push_back(l);
    }
    b.arms.push_back(arm);
  }
  return b;
}

inline blade::ContactLocation random_contact(std::mt19937_64& rng, const blade::Blade& b) {
  if (b.arms.empty() || integer(rng, 0, 5) == 0) return blade::ContactLocation::hub(uniform(rng, 0.05, 1.0) * b.hub.reach());
  const std::size_t a = static_cast<std::size_t>(integer(rng, 0, static_cast<int>(b.arms.size()) - 1));
  const std::size_t k = static_cast<std::size_t>(integer(rng, 0, static_cast<int>(b.arms[a].links.size()) - 1));
  return blade::ContactLocation::on_link(a, k, uniform(rng, 0.0, 1.0) * b.arms[a].links[k].length);
}

inline blade::StruckObject random_object(std::mt19937_64& rng, bool eccentric) {
  blade::StruckObject o;
  o.mass = std::exp(uniform(rng, std::log(0.001), std::log(5.0)));
  // Mostly moving toward the blade (-y) with some radial and vertical drift.
  o.velocity = {uniform(rng, -3.0, 3.0), uniform(rng, -5.0, 0.5), uniform(rng, -3.0, 3.0)};
  if (eccentric) {
    blade::Rod r;
    r.length = uniform(rng, 0.02, 0.1);
    r.transverse_inertia = o.mass * r.length * r.length / 12.0;
    r.axis = blade::Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)).normalized();
    r.offset = uniform(rng, -0.5, 0.5) * r.length;
    o.rod = r;
    o.spin = {uniform(rng, -10, 10), uniform(rng, -10, 10), uniform(rng, -10, 10)};
    o.spin -= o.spin.dot(r.axis) * r.axis;  // a slender rod has no spin about its own axis
  }
  return o;
}

}  // namespace j232::test
