#pragma once
// The impulse of one blade contact on the nail (docs/model.md §5.1c). At the contact point,
// with the geometric normal n (blade into nail), the velocity of the nail's point relative
// to the blade's point changes linearly with the impulse P on the nail: dv = K P, with
//     K = K_nail + K_blade,
//     K_nail  = I / m - [r]x I_n^-1 [r]x      (r: contact point from the nail's centre)
//     K_blade = B C B^T                       (C: the blade's planar compliance there,
//                                              B = [e_t e_r]: it yields only in its plane)
// The impulse is Poisson's restitution with Coulomb friction: first the sticking impulse
// (compression P_c = -K^-1 v_rel to zero relative velocity, then a restitution impulse
// along K^-1 n whose normal part is e times the compression's); if its tangential part
// needs more than mu times its normal part, the nail slides: P = P_n (n - mu t) with t the
// direction of the initial slip and P_n (1 + e) times the compression's. With friction the
// sliding impulse can create energy when the slip would reverse; the energy change of the
// two bodies, P . (v_rel + K P / 2), is checked, and e lowered until it is not positive (the
// perfectly inelastic sticking impulse never creates energy).
// Frictionless, with n along the blade's motion and the contact on the line of the nail's
// centre, this is report 445-1's central impact (blade/impact.hpp).
#include <Eigen/Dense>

#include "blade/blade.hpp"
#include "blade/restitution.hpp"
#include "projectile/projectile.hpp"
#include "strike/contact_search.hpp"
#include "strike/spindle.hpp"

namespace j232::strike {

struct ImpulseSolution {
  Vec3 impulse = Vec3::Zero();  // on the nail, N s
  double e = 0;                 // the restitution used
  bool sticking = false;
  double energy_change = 0;  // J, <= 0
  // Stronge's integration did not end within its step cap (a slip near the sticking limit
  // whose direction swings faster than its steps follow: rare, found by an independent
  // review in about 1 of 10 000 adversarial contacts, none in the shipped runs): the impulse
  // is then the legacy Poisson law's, which creates no energy and keeps Coulomb's cone.
  bool step_cap_fallback = false;
};

// How the restitution coefficient is read (docs/model.md §5.1c): Stronge's energetic
// coefficient, the restitution phase's normal work e^2 times the compression's, with
// friction integrated along the normal impulse (stick, slip, the slip halting and turning;
// never creating energy); or Poisson's impulse ratio with the slip held in its first
// direction (the law of earlier versions, kept for comparison: it can create energy with
// friction, and e is then lowered until it does not).
using RestitutionLaw = scenario::RestitutionLaw;
const char* restitution_law_name(RestitutionLaw l);  // "energetic", "poisson"

// Solves one impulse for the relative velocity v_rel (nail point minus blade point) with
// compliance K. `v_rel . n` must be negative (approaching).
ImpulseSolution solve_impulse(const Eigen::Matrix3d& K, const Vec3& v_rel, const Vec3& n, const blade::Restitution& law, double mu,
                              RestitutionLaw form = RestitutionLaw::Energetic);
ImpulseSolution solve_impulse_energetic(const Eigen::Matrix3d& K, const Vec3& v_rel, const Vec3& n, double e, double mu);
// Stronge's law in closed form where the normal and tangential motions do not couple and the
// tangential compliance is isotropic: K = knn n n^T + c (I - n n^T) (a ball's contact). What
// solve_impulse_energetic uses there (to round-off); `energy_change` is left for the caller.
ImpulseSolution decoupled_impulse(const Vec3& v_rel, const Vec3& n, double knn, double c, double e, double mu);
// Where a slip starting from rest heads when friction cannot hold the contact (k_n, K_tt: the
// tangential rows of K in a tangent basis; stick_rate = -K_tt^-1 k_n): the unit û along which
// k_n - mu K_tt û points (the slip grows along û against friction -mu û).
Eigen::Vector2d restart_direction(const Eigen::Vector2d& kn, const Eigen::Matrix2d& ktt, double mu, const Eigen::Vector2d& stick_rate);
ImpulseSolution solve_impulse_poisson(const Eigen::Matrix3d& K, const Vec3& v_rel, const Vec3& n, const blade::Restitution& law, double mu);

// The nail's inverse inertia (world), a rod with transverse inertia I_t and axial I_a.
Eigen::Matrix3d inverse_inertia(const projectile::Projectile& nail, const Vec3& axis);

// The nail's own compliance at the point r from its centre: K_nail = I / m - [r]x I_n^-1 [r]x
// (`inv_i`: its inverse inertia, inverse_inertia(nail, axis)).
Eigen::Matrix3d nail_compliance(const projectile::Projectile& nail, const Eigen::Matrix3d& inv_i, const Vec3& r);

struct StrikeOutcome {
  bool approaching = false;
  double approach_speed = 0;
  ImpulseSolution solution;
  Vec3 velocity_after = Vec3::Zero(), spin_after = Vec3::Zero();
  double blade_effective_mass = 0;   // along the tangent at the contact, kg
  blade::ContactLocation where;      // the blade body struck
  double energy_lost = 0;            // J, >= 0 (the impact's, before any push)
  // The driven blade's push after the impact (docs/model.md §5.2), where the body's point
  // still approaches the rigid blade's faster than the contact search's 1e-6 m/s: its impulse
  // on the body (N s) and the changes of velocity and spin it brings; zero elsewhere. Not in
  // velocity_after and spin_after (the impact's alone): a body the strike presses into the
  // soil is not pushed, the knife rides over it (flight::soil_reaction, ride_over).
  Vec3 push = Vec3::Zero(), push_velocity = Vec3::Zero(), push_spin = Vec3::Zero();
  Vec3 pushed_velocity() const { return velocity_after + push_velocity; }
  Vec3 pushed_spin() const { return spin_after + push_spin; }
};

// The contact `k` of `spindle` on the nail moving at `velocity` with `spin`.
StrikeOutcome strike(const Spindle& spindle, const Contact& k, const projectile::Projectile& nail, const Vec3& velocity, const Vec3& spin);

}  // namespace j232::strike
