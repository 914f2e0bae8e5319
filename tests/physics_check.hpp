#pragma once
// Independent bookkeeping for the impact tests: angular momentum and kinetic energy
// computed body by body from the kinematics of pinned rods, not from the mass matrix
// the code under test builds. If the model's M or J were wrong, these would disagree.
#include <vector>

#include "blade/blade_model.hpp"
#include "blade/impact.hpp"

namespace j232::test {

// Absolute angular velocity of the hub and of every link.
struct BladeRates {
  double hub = 0.0;
  std::vector<std::vector<double>> links;
};

inline BladeRates rigid(const blade::Blade& b) {
  BladeRates r{b.omega, {}};
  for (const auto& arm : b.arms) r.links.emplace_back(arm.links.size(), b.omega);
  return r;
}

inline BladeRates after(const blade::ImpactSolution& s) { return {s.hub_rate_after, s.link_rates}; }

// Tangential speed of link k's inner pin on arm a.
inline double pin_speed(const blade::Blade& b, const BladeRates& r, std::size_t a, std::size_t k) {
  double v = b.arms[a].pivot_radius * r.hub;
  for (std::size_t i = 0; i < k; ++i) v += b.arms[a].links[i].length * r.links[a][i];
  return v;
}

// Tangential speed of a point on the blade (any body), radially aligned configuration.
inline double point_speed(const blade::Blade& b, const BladeRates& r, const blade::ContactLocation& w) {
  if (w.on_hub) return w.distance * r.hub;
  return pin_speed(b, r, w.arm, w.link) + w.distance * r.links[w.arm][w.link];
}

// z angular momentum about the point at radius `rho` on arm `a`'s radial line, of links
// first_link.. of that arm. With first_link = 0 and rho = 0 summed over every arm plus
// the hub this is the whole blade's angular momentum about the spindle.
inline double arm_momentum(const blade::Blade& b, const BladeRates& r, std::size_t a, std::size_t first_link, double rho) {
  double h = 0.0;
  const auto& arm = b.arms[a];
  for (std::size_t k = first_link; k < arm.links.size(); ++k) {
    const auto& l = arm.links[k];
    const double vc = pin_speed(b, r, a, k) + l.centre() * r.links[a][k];
    const double rc = arm.pin_radius(k) + l.centre();
    h += l.inertia() * r.links[a][k] + l.mass * vc * (rc - rho);
  }
  return h;
}

inline double blade_momentum_about_spindle(const blade::Blade& b, const BladeRates& r) {
  double h = b.hub.inertia() * r.hub;
  for (std::size_t a = 0; a < b.arms.size(); ++a) h += arm_momentum(b, r, a, 0, 0.0);
  return h;
}

inline double blade_energy(const blade::Blade& b, const BladeRates& r) {
  double t = 0.5 * b.hub.inertia() * r.hub * r.hub;
  for (std::size_t a = 0; a < b.arms.size(); ++a)
    for (std::size_t k = 0; k < b.arms[a].links.size(); ++k) {
      const auto& l = b.arms[a].links[k];
      const double vc = pin_speed(b, r, a, k) + l.centre() * r.links[a][k];
      t += 0.5 * l.mass * vc * vc + 0.5 * l.inertia() * r.links[a][k] * r.links[a][k];
    }
  return t;
}

// The object in the struck arm's frame (x radial, y tangential, z up); contact point at (R, 0, 0).
struct ObjectState {
  blade::Vec3 velocity, spin;
};

inline blade::Vec3 object_centre(const blade::StruckObject& o, double contact_radius) {
  blade::Vec3 c(contact_radius, 0.0, 0.0);
  if (o.rod) c -= o.rod->offset * o.rod->axis;
  return c;
}

inline blade::Vec3 object_spin_momentum(const blade::StruckObject& o, const blade::Vec3& spin) {
  if (!o.rod) return blade::Vec3::Zero();
  const blade::Vec3 axis = o.rod->axis;
  return o.rod->transverse_inertia * (spin - spin.dot(axis) * axis);  // slender rod: no axial inertia
}

// z angular momentum of the object about the point (rho, 0, 0).
inline double object_momentum(const blade::StruckObject& o, double contact_radius, const ObjectState& s, double rho) {
  const blade::Vec3 arm = object_centre(o, contact_radius) - blade::Vec3(rho, 0.0, 0.0);
  return o.mass * arm.cross(s.velocity).z() + object_spin_momentum(o, s.spin).z();
}

inline double object_energy(const blade::StruckObject& o, const ObjectState& s) {
  return 0.5 * o.mass * s.velocity.squaredNorm() + 0.5 * s.spin.dot(object_spin_momentum(o, s.spin));
}

}  // namespace j232::test
