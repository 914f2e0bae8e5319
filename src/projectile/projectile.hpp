#pragma once
// What is thrown, as the contacts see it (docs/model.md §5.0): a rigid capsule, a
// segment of length L - D capped by hemispheres of radius D / 2, so that it spans the
// nail's whole length L end to end. Its mass is spread along the shank (a slender rod),
// so its inertia about the centre, across the axis, is m L^2 / 12, and about the axis
// that of a solid cylinder, m D^2 / 8 (the head's share of either is not modelled).
// A sphere (steel balls, stones) is the capsule of zero segment length.
#include <algorithm>

namespace j232::projectile {

struct Projectile {
  double length = 0;    // end to end, m
  double diameter = 0;  // m
  double mass = 0;      // kg

  static Projectile capsule(double length, double diameter, double mass) { return {length, diameter, mass}; }
  static Projectile sphere(double diameter, double mass) { return {diameter, diameter, mass}; }

  double radius() const { return 0.5 * diameter; }
  // Half the length of the core segment (centre to the centre of an end cap).
  double half_segment() const { return std::max(0.0, 0.5 * (length - diameter)); }
  double transverse_inertia() const {
    if (half_segment() == 0) return 0.1 * mass * diameter * diameter;  // a sphere: 2/5 m r^2
    return mass * length * length / 12.0;
  }
  double axial_inertia() const { return half_segment() == 0 ? transverse_inertia() : mass * diameter * diameter / 8.0; }
  // A rod's spin about its own axis (from friction at its surface) is left out after every
  // contact: it holds under 1/200 of the energy of its tumbling, and flight follows the axis
  // only. A sphere has no axis of its own: its whole spin is kept (a ball rolling along a
  // wall spins about the wall's vertical, whatever way its nominal axis points).
  template <class V>
  V without_axial_spin(const V& spin, const V& axis) const {
    return half_segment() == 0 ? spin : V(spin - spin.dot(axis) * axis);
  }
};

}  // namespace j232::projectile
