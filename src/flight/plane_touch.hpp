#pragma once
// Where a tumbling nail first touches a flat surface, and what the surface feels there
// (docs/model.md §5.5). The nail is the capsule of projectile/; between events its centre
// moves on a parabola and its axis turns about its spin (strike::Motion). A ray from the
// centre finds which surface the nail is heading for; the capsule touches that surface's
// plane earlier, at its point nearest the plane, turned as the spin has turned it then.
#include <optional>

#include "projectile/projectile.hpp"
#include "scenario/scenario.hpp"
#include "strike/contact_search.hpp"

namespace j232::flight {

using Vec3 = Eigen::Vector3d;

struct PlaneTouch {
  double time = 0;
  Vec3 centre = Vec3::Zero();  // the nail's centre then
  Vec3 axis = Vec3::UnitZ();   // and its axis
  Vec3 point = Vec3::Zero();   // the point of the capsule that touches, on the plane
  bool already = false;        // it was on (or through) the plane at the search's start
};

// The first time in [from, until] at which the capsule moving as `m` reaches the plane
// through `q` with unit normal `n` (pointing to the side the nail comes from), found by
// conservative advancement on its clearance n.(c - q) - h |n.a| - D/2 (h the half core
// segment) to within kTouchTolerance; if it already reaches the plane at `from`, then
// (unless `leaving`: it has just bounced off this plane, and only its nearest point moving
// into the plane again, or a touch after it has come clear, counts). Nothing when it stays clear until `until`.
inline constexpr double kTouchTolerance = 2e-6;  // m
std::optional<PlaneTouch> first_plane_touch(const strike::Motion& m, const projectile::Projectile& nail, const Vec3& q, const Vec3& n,
                                            double from, double until, bool leaving = false);

// The nail's mass as felt at a point r from its centre along the unit direction n: the
// impulse that stops that point's motion along n is m_eff times its speed, and the energy a
// perfectly plastic impact there takes out is m_eff v_n^2 / 2:
//     1 / m_eff = n . (I / m - [r]x I^-1 [r]x) n = 1/m + (r x n) . I^-1 (r x n).
double effective_mass(const projectile::Projectile& nail, const Vec3& axis, const Vec3& r, const Vec3& n);

// The nail's rebound off a surface with normal n (facing the nail) at the point `arm` from
// its centre: Poisson's restitution e and Coulomb friction mu through the impulse of
// strike/impulse.hpp, so that the bounce changes the spin as well as the velocity
// (docs/model.md §5.3). The surface is immovable, or (a flap swinging on its hinge) moves
// along n only, as a mass 1 / surface_inverse_mass at the contact, at rest before it. The
// spin about a rod's own axis is left out, as after a blade contact. Nothing happens
// when that point is not approaching.
void rebound(const projectile::Projectile& nail, const Vec3& axis, const Vec3& arm, const Vec3& n, double e, double mu, Vec3& velocity,
             Vec3& spin, double surface_inverse_mass = 0.0, scenario::RestitutionLaw law = scenario::RestitutionLaw::Energetic);

// A blade's strike on an object lying on the soil (a field's stone, flat turf at z = 0)
// that drives it into the soil: the soil takes the strike's downward part at once, with no
// rebound (a stone pressed into the ground does not spring back out of it), and its
// friction mu takes up to mu times that from the motion along the ground. Only for an
// object touching the soil (its lowest point within a millimetre of it, or in it) whose
// velocity points into it; otherwise nothing happens. Without it the rigid blade and rigid
// ground would trade impulses at one instant without end (a wedge). Returns whether it acted.
// `turf`: the ground's velocity (a field's, moving under the mower); friction acts on the
// slip against it. `support`: the height of what the object rests on (a field object's
// crown, clump or thatch above the plane the wheels ride on; 0: that plane).
bool soil_reaction(const Vec3& centre, double radius, double mu, const Vec3& turf, Vec3& velocity, double support = 0);

}  // namespace j232::flight
