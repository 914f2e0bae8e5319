#pragma once
// Free flight of a nail between contacts (docs/model.md §5.3): gravity, and optionally air
// drag per velocity component relative to the nail's axis. Without drag the path is an
// exact parabola; with drag it is integrated by classical RK4 with steps short enough
// that each step is also a chord whose sag stays under the tolerance.
#include <Eigen/Dense>

#include "units/quantity.hpp"

namespace j232::flight {

using Vec3 = Eigen::Vector3d;

struct Body {
  Vec3 position = Vec3::Zero();  // centre, m
  Vec3 velocity = Vec3::Zero();  // m/s
  Vec3 spin = Vec3::Zero();      // rad/s, perpendicular to the axis (a slender rod)
  Vec3 axis = Vec3::UnitZ();     // unit, tip -> head, at `time`
  double time = 0;
};

struct Drag {
  bool on = false;
  double k_axial = 0;       // rho C_a A_a / (2 m), 1/m
  double k_normal = 0;      // rho C_n A_n / (2 m), 1/m
  Vec3 air = Vec3::Zero();  // air velocity in the mower's frame (still air seen from a moving mower)
};

inline const Vec3 kGravity(0.0, 0.0, -units::standard_gravity);

// The axis after turning about the spin for dt (Rodrigues' rotation).
Vec3 rotate_axis(const Vec3& axis, const Vec3& spin, double dt);

// Drag acceleration at velocity v with the nail's axis along `axis`.
Vec3 drag_acceleration(const Drag& drag, const Vec3& velocity, const Vec3& axis);

// Gravity plus drag on the body as it is.
Vec3 acceleration(const Body& body, const Drag& drag);

// Advances the body by dt: exact parabola without drag, one RK4 step with it. The second
// form takes the body's acceleration(), already known (the chord's length needed it, and
// a step to a hit on the chord starts from the same body): one drag evaluation fewer.
Body advance(const Body& body, double dt, const Drag& drag);
Body advance(const Body& body, double dt, const Drag& drag, const Vec3& acceleration_at_start);

// The longest step whose chord sags less than `tolerance` and runs at most `max_length`,
// for a body with the given acceleration().
double chord_step(const Body& body, const Vec3& acceleration, double tolerance, double max_length);

}  // namespace j232::flight
