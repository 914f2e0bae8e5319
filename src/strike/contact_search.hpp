#pragma once
// When and where a turning blade first touches a moving, spinning capsule
// (docs/model.md §5.1b). The blade near each edge is its section (strike/blade_section)
// swept along the arm; the nail is a capsule whose centre moves as p0 + v0 s + a s^2 / 2
// (s = t - t0) while its axis turns about a fixed spin. The search is conservative
// advancement: far from an arm, by the angle the arm must still turn (or the height or
// radius the nail must still cross) over a bound on how fast that gap closes; near it, by
// the distance between the capsule and the section over a bound on how fast any point of
// the capsule moves in the blade's frame, but by no less than kMinStep of that motion. A
// step that finds the capsule overlapping the section is bisected back to the touch, so
// only a grazing touch shallower than kMinStep can pass unseen (docs/validation.md: the
// search against a fine fixed-step reference). A touch counts when
// the contact points approach each other; after an impulse the same search, from the
// contact, finds the next touch of the same pass (the nail turning back into the plate, or
// the plate catching it again) or the next pass.
#include <Eigen/Dense>
#include <cmath>
#include <optional>

#include "projectile/projectile.hpp"
#include "units/sin_cos.hpp"
#include "strike/spindle.hpp"

namespace j232::strike {

// An axis turning at a constant spin: a(dt) = along + across cos(w dt) + ortho sin(w dt)
// (Rodrigues' rotation, its fixed parts worked out once for the many instants a search
// looks at).
struct Turning {
  Vec3 start = Vec3::UnitZ(), along = Vec3::UnitZ(), across = Vec3::Zero(), ortho = Vec3::Zero();
  double rate = 0;  // w, rad/s
  Turning() = default;
  Turning(const Vec3& axis, const Vec3& spin);
  Vec3 at(double dt) const {
    if (rate * dt == 0.0) return start;
    const units::SinCos sc = units::sin_cos(rate * dt);
    return along + across * sc.cos + ortho * sc.sin;
  }
};

// A body moving freely over a short interval.
struct Motion {
  Vec3 p0 = Vec3::Zero(), v0 = Vec3::Zero(), a = Vec3::Zero();  // centre at t0, its velocity, a constant acceleration
  double t0 = 0;
  Vec3 axis0 = Vec3::UnitZ();  // unit, tip -> head, at t0
  Vec3 spin = Vec3::Zero();    // rad/s
  Vec3 centre(double t) const {
    const double s = t - t0;
    return p0 + v0 * s + 0.5 * s * s * a;
  }
  Vec3 velocity(double t) const { return v0 + (t - t0) * a; }
  Vec3 axis(double t) const;
  Turning turning() const { return {axis0, spin}; }
};

// The axis after turning about `spin` for dt (Rodrigues' rotation).
Vec3 turned(const Vec3& axis, const Vec3& spin, double dt);

struct Contact {
  std::size_t spindle = 0, edge = 0;
  double time = 0;
  Vec3 centre = Vec3::Zero();  // the nail's centre then
  Vec3 axis = Vec3::UnitZ();   // and its axis
  Vec3 point = Vec3::Zero();   // the contact, on the nail's surface, world
  Vec3 normal = Vec3::UnitY();  // unit, from the blade into the nail
  double radius = 0;            // of the contact along the arm, from the spindle's axis
  double forward_offset = 0;    // off the arm's edge line along the blade's motion (section u, <= 0: behind it), m
  Vec3 radial = Vec3::UnitX(), forward = Vec3::UnitY();  // the arm's frame then: along it, and the blade's motion
  int part = 0;                 // 0: the plate (edge, bevel, faces), 1: the sail
};

struct SearchStats {
  int steps = 0;             // advancement steps taken
  bool gave_up = false;      // the step cap was reached: the result is not known
};

inline constexpr double kContactTolerance = 2e-6;  // m: a capsule this close to the section touches it
inline constexpr double kMinStep = 2e-4;            // m: the least travel of a step near the blade (a tenth of a nail's diameter)
inline constexpr int kMaxSearchSteps = 4000;        // per edge and search
// A body turning with an arm just outside its window: kStallSteps window steps in a row,
// each shorter than the one before, bring in the exact distance's bound.
inline constexpr int kStallSteps = 32;
// m/s: at a search's start (just after an impulse), a touch approaching slower is no new contact
inline constexpr double kSameInstantApproach = 1e-6;
inline constexpr double kCoarseAtan2Error = 2e-5;   // rad: coarse_atan2's bound, with a margin

// atan2(y, x) to within kCoarseAtan2Error (for the search's angular bounds; exposed for tests).
double coarse_atan2(double y, double x);

// How the search steps: conservative advancement (production), or fixed steps of at most
// 10 um of relative motion testing the clearance at each (the reference it is validated
// against: docs/validation.md; `[run] contact_search = "fixed_steps"`, about 300 times slower).
enum class SearchMethod { Advancement, FixedSteps };

// The first approaching touch of any edge of `spindle` on the capsule in [motion.t0, t1],
// the blade standing at `phase` at time 0. `stats` accumulates.
std::optional<Contact> first_contact(const Spindle& spindle, double phase, const projectile::Projectile& nail, const Motion& motion,
                                     double t1, SearchStats& stats, SearchMethod method = SearchMethod::Advancement);

// The capsule's clearance from edge e's section at time t (< 0: overlapping; the part of
// the core beyond the arm's tip does not count), and whether its nearest points approach
// each other then. For tests and the fixed-step reference.
struct Clearance {
  double distance = 0;
  bool approaching = false;
  bool off_arm = false;
};
Clearance clearance(const Spindle& spindle, std::size_t e, double phase, const projectile::Projectile& nail, const Motion& motion, double t);

}  // namespace j232::strike
