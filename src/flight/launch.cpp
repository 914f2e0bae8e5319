#include "flight/launch.hpp"

#include <Eigen/Dense>

#include "flight/plane_touch.hpp"

namespace j232::flight {

Launch launch(const strike::Spindle& spindle, const strike::Contact& contact, const projectile::Projectile& body, const Vec3& coming) {
  Launch l;
  l.hit = strike::strike(spindle, contact, body, coming, Vec3::Zero());
  if (!l.hit.approaching) return l;
  if (!l.hit.velocity_after.allFinite() || !l.hit.spin_after.allFinite()) {
    l.result = Launch::Result::NonFinite;
    return l;
  }
  // The blade strikes a body when it gives it energy: one that merely lands on a blade too
  // slow to throw it (a stopped blade) is not thrown, and the test did not happen for it.
  const double energy_after = 0.5 * body.mass * l.hit.velocity_after.squaredNorm() +
                              0.5 * l.hit.spin_after.dot(strike::inverse_inertia(body, contact.axis).inverse() * l.hit.spin_after);
  if (!(energy_after > 0.5 * body.mass * coming.squaredNorm())) return l;
  l.result = Launch::Result::Thrown;
  l.body.position = contact.centre;
  // It leaves with the driven blade's push (no soil here: a field's object pressed into it
  // is the field simulator's to judge).
  l.body.velocity = l.hit.pushed_velocity();
  l.body.axis = contact.axis;
  l.body.spin = body.without_axial_spin(l.hit.pushed_spin(), l.body.axis);  // a rod's flight follows its axis; a sphere keeps its whole spin
  l.body.time = contact.time;  // the blades' clock: later contacts are timed against it
  return l;
}

AfterStrike after_strike(const strike::StrikeOutcome& hit, const strike::Spindle& spindle, const strike::Contact& contact,
                         const Vec3& centre, const StruckSoil* soil) {
  AfterStrike a;
  a.velocity = hit.velocity_after;
  if (soil && soil_reaction(centre, soil->reach, soil->friction, soil->turf, a.velocity, soil->support)) {
    a.spin = hit.spin_after;
    a.ride_over = (a.velocity + hit.spin_after.cross(contact.point - centre) - spindle.velocity_at(contact.point)).dot(contact.normal) <= 0;
    return a;
  }
  a.velocity = hit.pushed_velocity(), a.spin = hit.pushed_spin();
  return a;
}

}  // namespace j232::flight
