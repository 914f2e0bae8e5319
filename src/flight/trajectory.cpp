#include "flight/trajectory.hpp"

#include <algorithm>
#include <cmath>

#include "strike/contact_search.hpp"
#include "units/quantity.hpp"

namespace j232::flight {

namespace {

// Complete elliptic integrals of the first and second kind, K(m) and E(m) with parameter
// m = k^2 in [0, 1], together (they share a logarithm): the polynomial approximations
// 17.3.34 and 17.3.36 of Abramowitz and Stegun, Handbook of Mathematical Functions (1964),
// absolute error under 2e-8 (the tests compare the average they give with a numerical
// one). At m = 1, K is infinite and E(1) = 1.
struct Elliptic {
  double k, e;
};
Elliptic elliptic(double m) {
  const double m1 = std::max(1.0 - m, 1e-300), log_term = std::log(1.0 / m1);
  return {(((0.01451196212 * m1 + 0.03742563713) * m1 + 0.03590092383) * m1 + 0.09666344259) * m1 + 1.38629436112 +
              ((((0.00441787012 * m1 + 0.03328355346) * m1 + 0.06880248576) * m1 + 0.12498593597) * m1 + 0.5) * log_term,
          (((0.01736506451 * m1 + 0.04757383546) * m1 + 0.06260601220) * m1 + 0.44325141463) * m1 + 1 +
              ((((0.00526449639 * m1 + 0.04069697526) * m1 + 0.09200180037) * m1 + 0.24998368310) * m1) * log_term};
}

// The ripple of the averaged drag is k v^2 / (2 omega) in velocity: under 1 % of the speed
// when omega > 50 k v; and k v^2 / (4 omega^2) in position: under 0.3 mm for a 6d nail
// (k ~ 0.05 1/m) when omega > 100 k v.
constexpr double kAveragingSpin = 100;

// Whether a nail spinning at `spin_rate` (rad/s) with `velocity` turns so fast that its
// drag is its average over the turn (kAveragingSpin).
bool spin_averaged(const Drag& drag, const Vec3& velocity, double spin_rate) {
  return drag.spin_average && spin_rate > kAveragingSpin * std::max(drag.k_axial, drag.k_normal) * (velocity - drag.air).norm();
}

// Rodrigues' rotation of `axis` about the unit vector k by the angle whose cosine and sine are c, s.
Vec3 rotate(const Vec3& axis, const Vec3& k, double c, double s) { return axis * c + k.cross(axis) * s + k * (k.dot(axis)) * (1 - c); }
}  // namespace

Vec3 rotate_axis(const Vec3& axis, const Vec3& spin, double dt) { return strike::turned(axis, spin, dt); }

Vec3 drag_acceleration(const Drag& drag, const Vec3& velocity, const Vec3& axis) {
  const Vec3 v = velocity - drag.air;
  if (drag.sphere) return -(drag.k_normal * v.norm()) * v;
  const double va = v.dot(axis);
  const Vec3 vn = v - va * axis;
  return -(drag.k_axial * std::abs(va) * va) * axis - (drag.k_normal * vn.norm()) * vn;
}

TurnAveragedDrag::TurnAveragedDrag(const Drag& drag, const Vec3& velocity, const Vec3& spin_unit)
    : spin_unit_(spin_unit), air_(drag.air), k_normal_(drag.k_normal), k_axial_(drag.k_axial) {
  // S(m) = int_0^{pi/2} sin^2 sqrt(1 - m sin^2) = ((2m - 1) E + (1 - m) K) / 3m, by its
  // series for small m (the closed form cancels there).
  const Vec3 v = velocity - air_;
  const double speed2 = v.squaredNorm(), vs = v.dot(spin_unit_);
  const double m = speed2 > 0 ? std::clamp((speed2 - vs * vs) / speed2, 0.0, 1.0) : 0.0;
  const Elliptic ke = elliptic(m);
  e_ = ke.e;
  s_ = m > 1e-3 ? ((2 * m - 1) * ke.e + (1 - m) * ke.k) / (3 * m) : units::pi / 4 - 3 * units::pi / 32 * m - 5 * units::pi / 256 * m * m;
}

Vec3 TurnAveragedDrag::at(const Vec3& velocity) const {
  // The axis turns in the plane normal to the spin. With v = v_s s + v_p (v_p in that
  // plane) and theta the angle from v_p to the axis, averaged over theta:
  //   axial:  < |v_a| v_a a > = (4 / 3 pi) |v_p| v_p
  //   normal: < |v_n| v_n >   = (2 |v| / pi) (E(m) v_s s + (E(m) - S(m)) v_p).
  const Vec3 v = velocity - air_;
  const double vs = v.dot(spin_unit_);
  const Vec3 vp = v - vs * spin_unit_;
  return -(k_normal_ * 2 / units::pi * v.norm()) * (e_ * vs * spin_unit_ + (e_ - s_) * vp) - (k_axial_ * 4 / (3 * units::pi) * vp.norm()) * vp;
}

Vec3 averaged_drag_acceleration(const Drag& drag, const Vec3& velocity, const Vec3& spin_unit) {
  return TurnAveragedDrag(drag, velocity, spin_unit).at(velocity);
}

DragOverStep::DragOverStep(const Drag& drag, const Body& start) : drag_(&drag), rate_(start.spin.norm()) {
  averaged_ = drag.on && !drag.sphere && spin_averaged(drag, start.velocity, rate_);
  if (averaged_) turn_averaged_ = TurnAveragedDrag(drag, start.velocity, start.spin / rate_);
}

Vec3 DragOverStep::acceleration(const Vec3& velocity, const Vec3& axis) const {
  if (!drag_->on) return kGravity;
  return kGravity + (averaged_ ? turn_averaged_.at(velocity) : drag_acceleration(*drag_, velocity, axis));
}

Vec3 acceleration(const Body& b, const Drag& drag) { return DragOverStep(drag, b).acceleration(b.velocity, b.axis); }

Body advance(const Body& b, double dt, const Drag& drag) {
  const DragOverStep over_step(drag, b);
  return advance(b, dt, over_step, over_step.acceleration(b.velocity, b.axis));
}

Body advance(const Body& b, double dt, const DragOverStep& drag, const Vec3& acceleration_at_start) {
  Body out = b;
  out.time = b.time + dt;
  // The axis at mid-step and at the end from one sine and cosine (of the half turn; the
  // whole turn by the double-angle formulas): this runs for every chord.
  const double rate = b.spin.norm();
  Vec3 mid_axis = b.axis;
  if (rate * dt != 0.0) {
    const Vec3 k = b.spin / rate;
    const double half = 0.5 * rate * dt, ch = std::cos(half), sh = std::sin(half);
    mid_axis = rotate(b.axis, k, ch, sh);
    out.axis = rotate(b.axis, k, ch * ch - sh * sh, 2 * sh * ch);
    // The spin decays over the step (the axis turned at the step's starting rate: the
    // decay is a fraction of a per cent per chord).
    if (drag.on() && drag.spin_damping() > 0) out.spin = b.spin / (1 + drag.spin_damping() * rate * dt);
  }
  if (!drag.on()) {
    out.position = b.position + b.velocity * dt + 0.5 * kGravity * dt * dt;
    out.velocity = b.velocity + kGravity * dt;
    return out;
  }
  const Vec3 k1v = acceleration_at_start, k1x = b.velocity;
  const Vec3 k2v = drag.acceleration(b.velocity + 0.5 * dt * k1v, mid_axis), k2x = b.velocity + 0.5 * dt * k1v;
  const Vec3 k3v = drag.acceleration(b.velocity + 0.5 * dt * k2v, mid_axis), k3x = b.velocity + 0.5 * dt * k2v;
  const Vec3 k4v = drag.acceleration(b.velocity + dt * k3v, out.axis), k4x = b.velocity + dt * k3v;
  out.position = b.position + dt / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
  out.velocity = b.velocity + dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
  return out;
}

double chord_step(const Body& b, const Vec3& a, double tolerance, double max_length, const DragOverStep& drag) {
  // Sag of a chord over dt under a transverse acceleration a: a dt^2 / 8.
  const double speed = b.velocity.norm();
  const Vec3 along = speed > 0 ? Vec3(b.velocity / speed) : Vec3::UnitZ();
  const double transverse = (a - a.dot(along) * along).norm();
  double dt = transverse > 0 ? std::sqrt(8.0 * tolerance / transverse) : 1.0;
  if (speed > 0) dt = std::min(dt, max_length / speed);
  // A drag that follows the axis is sampled by the step's stages: they must see it turn.
  if (drag.follows_axis()) dt = std::min(dt, kMaxTurnPerStep / drag.spin_rate());
  return dt;
}

}  // namespace j232::flight
