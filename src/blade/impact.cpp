#include "blade/impact.hpp"

#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace j232::blade {

ContactOutcome resolve_contact(const BladeAtContact& blade, const StruckObject& object, const Restitution& restitution) {
  ContactOutcome out;
  const Vec3& n = blade.normal;
  Vec3 arm = Vec3::Zero();  // contact point relative to the object's centre
  double rotational_compliance = 0.0;
  Vec3 lever = Vec3::Zero();  // r x n
  if (object.rod) {
    arm = object.rod->offset * object.rod->axis;
    lever = arm.cross(n);
    rotational_compliance = lever.squaredNorm() / object.rod->transverse_inertia;
  }
  const Vec3 point_velocity = object.velocity + object.spin.cross(arm);
  out.approach_speed = blade.speed - point_velocity.dot(n);
  out.velocity_after = object.velocity;
  out.spin_after = object.spin;
  out.blade_speed_before = blade.speed;
  out.blade_speed_after = blade.speed;
  const double object_compliance = 1.0 / object.mass + rotational_compliance;
  out.object_effective_mass = 1.0 / object_compliance;
  if (!(out.approach_speed > 0.0)) return out;

  out.approaching = true;
  const double blade_compliance = std::isinf(blade.effective_mass) ? 0.0 : 1.0 / blade.effective_mass;
  const double reduced = 1.0 / (blade_compliance + object_compliance);
  out.e = restitution.at(out.approach_speed);
  out.impulse = (1.0 + out.e) * out.approach_speed * reduced;
  out.energy_lost = 0.5 * (1.0 - out.e * out.e) * out.approach_speed * out.approach_speed * reduced;
  out.velocity_after = object.velocity + (out.impulse / object.mass) * n;
  if (object.rod) out.spin_after = object.spin + (out.impulse / object.rod->transverse_inertia) * lever;
  out.blade_speed_after = blade.speed - out.impulse * blade_compliance;
  return out;
}

ImpactSolution solve_impact(const BladeModel& model, const ContactLocation& where, const StruckObject& object,
                            const Restitution& restitution) {
  if (auto p = restitution.problem(); !p.empty()) throw std::invalid_argument(p);
  ImpactSolution s;
  s.location = where;
  s.contact_radius = contact_radius(model.blade(), where);
  s.blade_effective_mass = model.effective_mass(where);

  BladeAtContact at;
  at.effective_mass = s.blade_effective_mass;
  at.speed = model.contact_speed(where);
  at.normal = Vec3::UnitY();  // arm along +x turning about +z moves along +y
  s.contact = resolve_contact(at, object, restitution);
  if (!s.contact.approaching)
    throw std::invalid_argument(
        fmt::format("no impact: the object's contact point moves at {:.4g} m/s along the blade's motion, not slower than the "
                    "blade's {:.4g} m/s, so the blade never catches it",
                    at.speed - s.contact.approach_speed, at.speed));

  // The blade receives the reaction: -P along its motion.
  const Eigen::VectorXd before = model.rigid_rates();
  const Eigen::VectorXd after = model.rates_after(where, -s.contact.impulse);
  s.hub_rate_after = model.hub_rate(after);
  const Blade& blade = model.blade();
  s.link_rates.resize(blade.arms.size());
  for (std::size_t a = 0; a < blade.arms.size(); ++a)
    for (std::size_t k = 0; k < blade.arms[a].links.size(); ++k) s.link_rates[a].push_back(model.link_rate(after, a, k));
  s.blade_energy_before = model.kinetic_energy(before);
  s.blade_energy_after = model.kinetic_energy(after);
  return s;
}

}  // namespace j232::blade
