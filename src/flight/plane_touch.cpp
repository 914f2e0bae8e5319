#include "flight/plane_touch.hpp"

#include <algorithm>
#include <cmath>

#include "flight/first_root.hpp"
#include "flight/regula_falsi.hpp"

#include "blade/restitution.hpp"
#include "strike/impulse.hpp"

namespace j232::flight {

namespace {
// The capsule's clearance from the plane, and its point nearest the plane.
double clearance(const projectile::Projectile& nail, const Vec3& centre, const Vec3& axis, const Vec3& q, const Vec3& n, Vec3* point) {
  const double h = nail.half_segment(), along = n.dot(axis);
  // The end of the core segment nearest the plane (the middle when it lies parallel).
  const Vec3 core = along > 0 ? Vec3(centre - h * axis) : along < 0 ? Vec3(centre + h * axis) : centre;
  if (point) *point = core - nail.radius() * n;
  return n.dot(centre - q) - h * std::abs(along) - nail.radius();
}
// The axis along n as it turns about the spin k: n . a(t) = c + A cos(wt) + B sin(wt), so
// |n . a| reaches at most |c| + sqrt(A^2 + B^2) (`reach`: exact, and constant, without
// spin) and changes at most w sqrt(A^2 + B^2) per second (`swing_rate`).
struct AxisAlongNormal {
  double reach = 0, swing_rate = 0;
};
AxisAlongNormal axis_along(const strike::Motion& m, const Vec3& n) {
  const double w = m.spin.norm();
  if (!(w > 0)) return {std::abs(n.dot(m.axis0)), 0.0};
  const Vec3 k = m.spin / w;
  const Vec3 along = k.dot(m.axis0) * k, across = m.axis0 - along;
  const double a = n.dot(across), b = n.dot(k.cross(across)), turning = std::sqrt(a * a + b * b);
  return {std::abs(n.dot(along)) + turning, w * turning};
}

}  // namespace

std::optional<PlaneTouch> first_plane_touch(const strike::Motion& m, const projectile::Projectile& nail, const Vec3& q, const Vec3& n,
                                            double from, double until, bool leaving) {
  // How fast the clearance can fall: the centre's speed along n (linear in time, so at most
  // its larger end value) and the core's ends swinging about the centre along n.
  const double centre_speed = std::max(std::abs(n.dot(m.velocity(from))), std::abs(n.dot(m.velocity(until))));
  const AxisAlongNormal axis = axis_along(m, n);
  const double bound = centre_speed + nail.half_segment() * axis.swing_rate + 1e-9;
  // Steps of at least this much motion: a touch shallower than it can be missed (as the
  // blade's search, strike/contact_search.hpp); an overlap found is bisected back.
  constexpr double kMinStep = 2e-4;  // m
  const strike::Turning turning = m.turning();
  // The clearance at t (and, when asked, the point nearest the plane and the axis then).
  const auto state = [&](double t, Vec3* point, Vec3* axis_then = nullptr) {
    const Vec3 a = turning.at(t - m.t0);
    if (axis_then) *axis_then = a;
    return clearance(nail, m.centre(t), a, q, n, point);
  };
  // Whether the capsule's point nearest the plane moves into it at t.
  const auto approaching = [&](double t) {
    Vec3 point;
    state(t, &point);
    return n.dot(m.velocity(t) + m.spin.cross(Vec3(point - m.centre(t)))) < 0;
  };
  Vec3 a_t;  // the axis at t, kept with g for the step from t
  double t = from, g = state(t, nullptr, &a_t);
  // Just bounced off this plane: the touch it is leaving is not a new one. While the nail is
  // still on the plane, only its nearest point moving into it again (the same end, or the
  // other one come round) is a touch; nothing if it stays on it, leaving, until `until`.
  bool already = g <= kTouchTolerance;
  while (leaving && g <= kTouchTolerance && !approaching(t)) {
    if (t >= until) return std::nullopt;
    t = std::min(until, t + kMinStep / bound), g = state(t, nullptr, &a_t);
  }
  if (g <= kTouchTolerance) until = t;  // touching already
  else already = false;
  // Far from the plane no stepping is needed: however the axis turns about the spin, the
  // core reaches at most h M along -n (M = axis.reach), so the centre's height above the
  // plane, a quadratic in time, must first come down to h M + D/2 (the swept disc's reach).
  // (Checked again at every step: a nail that leaves the plane's near field crosses the
  // rest of the interval in one step.)
  const double reach = nail.half_segment() * axis.reach + nail.radius() + kTouchTolerance;
  const auto far_field = [&](double t_now) {
    const double above = n.dot(m.centre(t_now) - q) - reach;
    return above > 0 ? first_root(above, n.dot(m.velocity(t_now)), n.dot(m.a)) : 0.0;
  };
  // Near it, each end's clearance f = n.(c - q) -+ h n.a - D/2 is smooth, with
  // |f''| <= |n.acc| + h w^2 R (R = axis.swing_rate / w): the first root of its Taylor lower
  // bound f + f' s - M s^2 / 2 is a safe step, much longer than the first-order one
  // (g / bound) unless the nail tumbles fast. The longer of the two is taken.
  const double h = nail.half_segment();
  const double curvature = std::abs(n.dot(m.a)) + h * m.spin.norm() * axis.swing_rate + 1e-9;
  const auto second_order = [&](double t_now, const Vec3& a) {
    const double p = n.dot(m.centre(t_now) - q) - nail.radius(), dp = n.dot(m.velocity(t_now));
    const double sv = h * n.dot(a), ds = h * n.dot(m.spin.cross(a));
    double step = HUGE_VAL;
    for (const double sign : {-1.0, 1.0}) {
      const double f = p + sign * sv, df = dp + sign * ds;
      step = std::min(step, f > 0 ? (df + std::sqrt(df * df + 2 * curvature * f)) / curvature : 0.0);
    }
    return step;
  };
  // A step into the plane is brought back to the touch by regula falsi (Illinois) on the
  // clearance, to within the tolerance.
  const auto refine = [&](double lo, double g_lo, double hi, double g_hi) {
    g_lo -= kTouchTolerance, g_hi -= kTouchTolerance;  // the root sought: clearance = tolerance
    return illinois_root(
        lo, g_lo, hi, g_hi, [&](double t_mid) { return state(t_mid, nullptr) - kTouchTolerance; }, bound, kTouchTolerance, 60,
        [](double, double g_mid) { return g_mid <= 0 && g_mid >= -kTouchTolerance; });  // within the tolerance of the plane
  };
  int steps = 0;
  for (; g > kTouchTolerance && steps < 100000; ++steps) {
    if (t >= until) return std::nullopt;
    if (const double x = far_field(t); x > std::max(g, kMinStep) / bound) {
      if (!(t + x <= until)) return std::nullopt;
      t += x, g = state(t, nullptr, &a_t);
      continue;
    }
    const double step = std::max(std::max(g, kMinStep) / bound, second_order(t, a_t));
    const double next = std::min(until, t + step);
    Vec3 a_next;
    const double g_next = state(next, nullptr, &a_next);
    if (g_next > kTouchTolerance) {
      t = next, g = g_next, a_t = a_next;
      continue;
    }
    // Through the plane within the step: back to the first instant within tolerance.
    t = refine(t, g, next, g_next), g = 0;
  }
  if (g > kTouchTolerance) return std::nullopt;  // the step cap: no touch found (never seen)
  PlaneTouch touch;
  touch.already = already && t == from;
  touch.time = t;
  touch.centre = m.centre(t);
  touch.axis = turning.at(t - m.t0);
  clearance(nail, touch.centre, touch.axis, q, n, &touch.point);
  // On the plane itself (the clearance is within the tolerance, or an overlap at `from`).
  touch.point -= n.dot(touch.point - q) * n;
  return touch;
}

void rebound(const projectile::Projectile& nail, const Vec3& axis, const Vec3& arm, const Vec3& n, double e, double mu, Vec3& velocity,
             Vec3& spin, double surface_inverse_mass, scenario::RestitutionLaw law) {
  const Vec3 v_point = velocity + spin.cross(arm);
  if (!(v_point.dot(n) < 0)) return;
  const Eigen::Matrix3d inv_i = strike::inverse_inertia(nail, axis);
  const Eigen::Matrix3d K = strike::nail_compliance(nail, inv_i, arm) + surface_inverse_mass * n * n.transpose();
  const Vec3 P = strike::solve_impulse(K, v_point, n, blade::Restitution::constant(std::clamp(e, 0.0, 1.0)), mu, law).impulse;
  velocity += P / nail.mass;
  spin += inv_i * arm.cross(P);
  spin = nail.without_axial_spin(spin, axis);  // (as after a blade contact)
}

double effective_mass(const projectile::Projectile& nail, const Vec3& axis, const Vec3& r, const Vec3& n) {
  const Vec3 rn = r.cross(n);
  return 1.0 / (1.0 / nail.mass + rn.dot(strike::inverse_inertia(nail, axis) * rn));
}

bool soil_reaction(const Vec3& centre, double radius, double mu, const Vec3& turf, Vec3& velocity, double support) {
  if (!(centre.z() - radius <= support + 1e-3) || !(velocity.z() < 0)) return false;
  const double into = -velocity.z();
  velocity.z() = 0;
  const double sx = velocity.x() - turf.x(), sy = velocity.y() - turf.y();  // the slip over the turf
  const double along = std::hypot(sx, sy);
  if (along > 0) {
    const double kept = std::max(0.0, along - mu * into) / along;
    velocity.x() = turf.x() + sx * kept, velocity.y() = turf.y() + sy * kept;
  }
  return true;
}

}  // namespace j232::flight
