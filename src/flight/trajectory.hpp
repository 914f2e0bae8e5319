#pragma once
// Free flight of a nail between contacts (docs/model.md §5.3): gravity, and optionally air
// drag per velocity component relative to the nail's axis. Without drag the path is an
// exact parabola; with drag it is integrated by classical RK4 with steps short enough
// that each step is also a chord whose sag stays under the tolerance. A struck nail
// spins at thousands of rad/s, its axis turning through many radians within a step: its
// drag is then taken as the average over the axis's turn about the spin (in closed form),
// which a step resolves; a slower spinner's steps are kept short enough to follow its axis.
#include <Eigen/Dense>

#include "units/quantity.hpp"

namespace j232::flight {

using Vec3 = Eigen::Vector3d;

struct Body {
  Vec3 position = Vec3::Zero();  // centre, m
  Vec3 velocity = Vec3::Zero();  // m/s
  Vec3 spin = Vec3::Zero();      // rad/s, perpendicular to a rod's axis (a sphere's: any way)
  Vec3 axis = Vec3::UnitZ();     // unit, tip -> head, at `time`
  double time = 0;
};

struct Drag {
  bool on = false;
  double k_axial = 0;       // rho C_a A_a / (2 m), 1/m
  double k_normal = 0;      // rho C_n A_n / (2 m), 1/m
  Vec3 air = Vec3::Zero();  // air velocity in the mower's frame (still air seen from a moving mower)
  bool spin_average = true;  // false: always the drag as the axis stands ([air] spin_average: the resolved reference)
  // The tumbling slowed by the cross-flow drag on the turning shank: d|w|/dt = -k_spin |w|^2
  // (strip theory: the torque of rho C_n D (w s)^2 / 2 per length about the centre over
  // the inertia m L^2 / 12 gives k_spin = 3 rho C_n D L^2 / (16 m); docs/model.md §5.3).
  double k_spin = 0;  // 1/rad
  // A sphere (a field's stone): the same drag whichever way it moves, -k_normal |v| v.
  bool sphere = false;
};

inline const Vec3 kGravity(0.0, 0.0, -units::standard_gravity);

// The axis after turning about the spin for dt (Rodrigues' rotation).
Vec3 rotate_axis(const Vec3& axis, const Vec3& spin, double dt);

// Drag acceleration at velocity v with the nail's axis along `axis`.
Vec3 drag_acceleration(const Drag& drag, const Vec3& velocity, const Vec3& axis);

// Drag acceleration averaged over a turn of the axis about `spin_unit` (the axis
// perpendicular to it, a slender rod's case), at velocity v.
Vec3 averaged_drag_acceleration(const Drag& drag, const Vec3& velocity, const Vec3& spin_unit);

// The same, ready for velocities near `velocity`: the elliptic integrals of the direction
// of `velocity` to the spin worked out once (a step's stages share them).
class TurnAveragedDrag {
 public:
  TurnAveragedDrag() = default;
  TurnAveragedDrag(const Drag& drag, const Vec3& velocity, const Vec3& spin_unit);
  Vec3 at(const Vec3& velocity) const;

 private:
  Vec3 spin_unit_ = Vec3::UnitZ(), air_ = Vec3::Zero();
  double k_normal_ = 0, k_axial_ = 0, e_ = 0, s_ = 0;
};

// The drag over one step from a body: as the axis stands, or averaged over its turn when
// the nail spins fast enough (spin_averaged at the step's start, E(m) and S(m) of its
// start: the velocity's direction barely turns within a step). Made once per chord and
// shared by its length, its step and a step to a hit on it.
class DragOverStep {
 public:
  DragOverStep(const Drag& drag, const Body& start);
  bool on() const { return drag_->on; }
  // Drag that turns with the axis, of a spinning nail: its steps must follow the turn.
  bool follows_axis() const { return drag_->on && !drag_->sphere && !averaged_ && rate_ > 0; }
  double spin_rate() const { return rate_; }
  double spin_damping() const { return drag_->k_spin; }
  // Gravity plus drag at this velocity with the axis there.
  Vec3 acceleration(const Vec3& velocity, const Vec3& axis) const;

 private:
  const Drag* drag_;
  double rate_;
  bool averaged_ = false;
  TurnAveragedDrag turn_averaged_;
};

// Gravity plus drag on the body as it is.
Vec3 acceleration(const Body& body, const Drag& drag);

// Advances the body by dt: exact parabola without drag, one RK4 step with it. The second
// form takes the step's drag and the body's acceleration, already known (the chord's
// length needed them, and a step to a hit on the chord starts from the same body).
Body advance(const Body& body, double dt, const Drag& drag);
Body advance(const Body& body, double dt, const DragOverStep& drag, const Vec3& acceleration_at_start);

// The longest step whose chord sags less than `tolerance` and runs at most `max_length`,
// for a body with the given acceleration; for a drag that follows the axis, also one in
// which the axis turns at most kMaxTurnPerStep.
inline constexpr double kMaxTurnPerStep = 0.3;  // rad
double chord_step(const Body& body, const Vec3& acceleration, double tolerance, double max_length, const DragOverStep& drag);

}  // namespace j232::flight
