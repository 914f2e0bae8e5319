#pragma once
// The impact core: one impulsive contact between the blade and a struck object
// (report 445-1 Chapter 2, generalised; docs/model.md §2–3).
//
// The blade side is reduced to two numbers at the contact: its effective mass m_b
// (BladeModel::effective_mass) and the speed v_p of the contact point along the
// contact normal n, which is the blade's direction of motion there. The object is a
// rigid body of mass m; if it is a slender rod struck off its centre (a nail hit
// above or below its middle) the contact point sits at r from its centre and the
// object's effective mass along n drops to
//     1 / m_o = 1 / m + |r x n|^2 / I_t.
// With the approach speed v = v_p - (u + w x r) . n > 0 and restitution e(v), the
// impulse on the object is P = (1 + e) v / (1 / m_b + 1 / m_o); the object leaves with
//     u' = u + P n / m,    w' = w + (r x n) P / I_t,
// and the contact dissipates 1/2 (1 - e^2) v^2 / (1 / m_b + 1 / m_o).
// The contact is frictionless (the report's central impact); friction and edge bevel
// belong to the strike model that chooses n.
#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "blade/blade_model.hpp"
#include "blade/restitution.hpp"

namespace j232::blade {

using Vec3 = Eigen::Vector3d;

// A slender rod (the nail) for eccentric impact.
struct Rod {
  double length = 0.0;              // m
  double transverse_inertia = 0.0;  // about its centre, perpendicular to the axis, kg m^2 (m L^2 / 12)
  Vec3 axis = Vec3::UnitZ();        // unit vector along the rod
  double offset = 0.0;              // contact point's distance from the centre along `axis`, m
};

struct StruckObject {
  double mass = 0.0;
  Vec3 velocity = Vec3::Zero();  // of the centre of mass, m/s
  Vec3 spin = Vec3::Zero();      // rad/s
  std::optional<Rod> rod;        // absent: a central impact (the report's assumption)
};

// The blade at the contact, reduced.
struct BladeAtContact {
  double effective_mass = kInfiniteMass;  // kg
  double speed = 0.0;                     // contact point speed along the normal before impact, m/s
  Vec3 normal = Vec3::UnitY();            // unit: the blade's direction of motion at the contact
};

struct ContactOutcome {
  bool approaching = false;  // false: the object outruns the blade; nothing happened
  double approach_speed = 0.0;
  double e = 0.0;
  double impulse = 0.0;                // on the object, along +normal, N s
  double object_effective_mass = 0.0;  // along the normal, kg
  double energy_lost = 0.0;            // J, >= 0
  double blade_speed_before = 0.0;     // contact point, along the normal
  double blade_speed_after = 0.0;
  Vec3 velocity_after = Vec3::Zero();
  Vec3 spin_after = Vec3::Zero();
};

// The per-nail core: no allocation, a few dozen flops.
ContactOutcome resolve_contact(const BladeAtContact& blade, const StruckObject& object, const Restitution& restitution);

// Full single-impact solution (report 445-1, Appendix A, second program), in the frame
// of the struck arm: x radial outward, y tangential (the blade's motion), z up.
struct ImpactSolution {
  ContactLocation location;
  double contact_radius = 0.0;
  double blade_effective_mass = 0.0;
  ContactOutcome contact;
  double hub_rate_after = 0.0;                  // rad/s
  std::vector<std::vector<double>> link_rates;  // [arm][link], absolute, rad/s
  double blade_energy_before = 0.0;             // free bodies only (a constant-speed hub's is the drive's)
  double blade_energy_after = 0.0;
};

// Throws std::invalid_argument when the object is not approaching the blade.
ImpactSolution solve_impact(const BladeModel& model, const ContactLocation& where, const StruckObject& object,
                            const Restitution& restitution);

}  // namespace j232::blade
