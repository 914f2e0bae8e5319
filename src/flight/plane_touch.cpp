#include "flight/plane_touch.hpp"

#include <algorithm>
#include <cmath>

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
}  // namespace

std::optional<PlaneTouch> first_plane_touch(const strike::Motion& m, const projectile::Projectile& nail, const Vec3& q, const Vec3& n,
                                            double from, double until, bool leaving) {
  // How fast the clearance can fall: the centre's speed along n (linear in time, so at most
  // its larger end value) and the core's ends swinging about the centre.
  const double centre_speed = std::max(std::abs(n.dot(m.velocity(from))), std::abs(n.dot(m.velocity(until))));
  const double bound = centre_speed + nail.half_segment() * m.spin.norm() + 1e-9;
  // Steps of at least this much motion: a touch shallower than it can be missed (as the
  // blade's search, strike/contact_search.hpp); an overlap found is bisected back.
  constexpr double kMinStep = 2e-4;  // m
  const auto state = [&](double t, Vec3* point) { return clearance(nail, m.centre(t), m.axis(t), q, n, point); };
  double t = from, g = state(t, nullptr);
  // Just bounced off this plane: the touch it is leaving is not a new one; the search starts
  // once the nail has come clear of the plane (nothing if it stays on it until `until`).
  while (leaving && g <= kTouchTolerance) {
    if (t >= until) return std::nullopt;
    t = std::min(until, t + kMinStep / bound), g = state(t, nullptr);
  }
  if (g <= kTouchTolerance) until = t;  // touching already
  for (int steps = 0; g > kTouchTolerance && steps < 100000; ++steps) {
    if (t >= until) return std::nullopt;
    const double next = std::min(until, t + std::max(g, kMinStep) / bound);
    const double g_next = state(next, nullptr);
    if (g_next > kTouchTolerance) {
      t = next, g = g_next;
      continue;
    }
    // Through the plane within the step: back to the first instant within tolerance.
    double lo = t, hi = next;
    for (int it = 0; it < 60 && hi - lo > 1e-12; ++it) {
      const double mid = 0.5 * (lo + hi);
      (state(mid, nullptr) > kTouchTolerance ? lo : hi) = mid;
    }
    t = hi, g = 0;
  }
  PlaneTouch touch;
  touch.time = t;
  touch.centre = m.centre(t);
  touch.axis = m.axis(t);
  clearance(nail, touch.centre, touch.axis, q, n, &touch.point);
  // On the plane itself (the clearance is within the tolerance, or an overlap at `from`).
  touch.point -= n.dot(touch.point - q) * n;
  return touch;
}

void rebound(const projectile::Projectile& nail, const Vec3& axis, const Vec3& arm, const Vec3& n, double e, double mu, Vec3& velocity,
             Vec3& spin) {
  const Vec3 v_point = velocity + spin.cross(arm);
  if (!(v_point.dot(n) < 0)) return;
  const Eigen::Matrix3d inv_i = strike::inverse_inertia(nail, axis);
  Eigen::Matrix3d R;
  R << 0, -arm.z(), arm.y(), arm.z(), 0, -arm.x(), -arm.y(), arm.x(), 0;
  const Eigen::Matrix3d K = Eigen::Matrix3d::Identity() / nail.mass - R * inv_i * R;
  const Vec3 P = strike::solve_impulse(K, v_point, n, blade::Restitution::constant(std::clamp(e, 0.0, 1.0)), mu).impulse;
  velocity += P / nail.mass;
  spin += inv_i * arm.cross(P);
  spin -= spin.dot(axis) * axis;  // the spin about the nail's own axis is left out (as after a blade contact)
}

double effective_mass(const projectile::Projectile& nail, const Vec3& axis, const Vec3& r, const Vec3& n) {
  const Vec3 rn = r.cross(n);
  return 1.0 / (1.0 / nail.mass + rn.dot(strike::inverse_inertia(nail, axis) * rn));
}

}  // namespace j232::flight
