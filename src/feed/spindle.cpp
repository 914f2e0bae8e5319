#include "feed/spindle.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "units/quantity.hpp"

namespace j232::feed {

namespace {
constexpr double kSampleAngle = 0.3;  // rad: the edge-to-nail angle is sampled at least this finely
}  // namespace

Spindle::Spindle(const blade::Blade& b, const scenario::BladeGeometry& g, const blade::Restitution& e)
    : height(g.height), thickness(g.thickness), lift_angle(g.lift_angle), blade(b), model(b), edges(leading_edges(b)), restitution(e) {
  for (const auto& edge : edges) reach = std::max(reach, edge.reach);
}

SweptRod::SweptRod(double length, const Eigen::Vector3d& axis, const Eigen::Vector3d& spin)
    : length_(length), rate_(spin.norm()), axis_(axis) {
  if (rate_ > 0) across_ = (spin / rate_).cross(axis);
  const double reach_up = rate_ > 0 ? std::min(1.0, std::sqrt(axis.z() * axis.z() + across_.z() * across_.z())) : std::abs(axis.z());
  max_half_height_ = 0.5 * length * reach_up;
}

double SweptRod::axis_z_after(double dt) const {
  if (rate_ == 0) return axis_.z();
  const double turn = rate_ * dt;
  return axis_.z() * std::cos(turn) + across_.z() * std::sin(turn);
}

std::optional<BladeHit> first_sweep(const Spindle& sp, double phase, const Eigen::Vector3d& p0, const Eigen::Vector3d& v, double t0,
                                    double t1, const SweptRod& rod, double after) {
  double lo = std::max(t0, after), hi = t1;
  if (!(hi > lo)) return std::nullopt;
  // The window is found with the most the turning nail reaches up or down; each edge pass
  // is then checked with the axis at that instant.
  const double half_height = rod.max_half_height();
  const auto in_slab_at = [&](double t) {
    return std::abs(p0.z() + v.z() * (t - t0) - sp.height) <= 0.5 * sp.thickness + 0.5 * rod.length() * std::abs(rod.axis_z_after(t - t0)) + 1e-12;
  };
  // In the slab: |z(t) - height| <= thickness / 2 + half_height, z linear in t.
  const double band = 0.5 * sp.thickness + half_height;
  const double dz = p0.z() - sp.height;
  if (v.z() == 0.0) {
    if (std::abs(dz) > band) return std::nullopt;
  } else {
    double ta = t0 + (-band - dz) / v.z(), tb = t0 + (band - dz) / v.z();
    if (ta > tb) std::swap(ta, tb);
    lo = std::max(lo, ta), hi = std::min(hi, tb);
    if (!(hi > lo)) return std::nullopt;
  }
  // Within the tip circle: |q(t)|^2 <= reach^2 with q the horizontal offset from the axis.
  const Eigen::Vector2d q0 = p0.head<2>() - sp.centre, w = v.head<2>();
  const double a = w.squaredNorm(), b = 2 * q0.dot(w), c = q0.squaredNorm() - sp.reach * sp.reach;
  if (a == 0.0) {
    if (c > 0) return std::nullopt;
  } else {
    // Roots in s = t - t0.
    const double disc = b * b - 4 * a * c;
    if (disc < 0) return std::nullopt;
    const double root = std::sqrt(disc);
    lo = std::max(lo, t0 + (-b - root) / (2 * a)), hi = std::min(hi, t0 + (-b + root) / (2 * a));
    if (!(hi > lo)) return std::nullopt;
  }

  // For each edge, the angle from the nail to the edge, unwrapped, sampled finely enough
  // that it cannot pass a whole multiple of 2 pi between samples unseen, then solved for
  // the crossing. Along a straight chord the nail's azimuth turns one way only, through the
  // angle the chord subtends at the axis (at most pi), so that angle and the edge's turn
  // bound it. The nail's azimuth at the samples is the same for every edge: worked out
  // once (the first kCached samples; a longer sweep works out the rest as it goes).
  const double omega = sp.sense * sp.omega();
  const auto q_at = [&](double t) -> Eigen::Vector2d { return q0 + w * (t - t0); };
  const Eigen::Vector2d q_lo = q_at(lo), q_hi = q_at(hi);
  const double subtended = std::abs(std::atan2(q_lo.x() * q_hi.y() - q_lo.y() * q_hi.x(), q_lo.dot(q_hi)));
  const int samples = 1 + static_cast<int>(std::ceil((std::abs(omega) * (hi - lo) + subtended) / kSampleAngle));
  const auto sample_time = [&](int k) { return lo + (hi - lo) * k / samples; };
  // The azimuth at t unwrapped to lie within pi of `near`.
  const auto azimuth_near = [&](double t, double near) {
    const Eigen::Vector2d q = q_at(t);
    return near + std::remainder(std::atan2(q.y(), q.x()) - near, units::two_pi);
  };
  constexpr int kCached = 64;
  std::array<double, kCached> cached;
  cached[0] = std::atan2(q_lo.y(), q_lo.x());
  int filled = 1;
  const auto azimuth_at = [&](int k, double previous) {  // sample k's azimuth, given sample k - 1's
    if (k < filled) return cached[static_cast<std::size_t>(k)];
    const double azimuth = azimuth_near(sample_time(k), previous);
    if (k == filled && k < kCached) cached[static_cast<std::size_t>(filled++)] = azimuth;
    return azimuth;
  };
  std::optional<BladeHit> best;
  for (std::size_t e = 0; e < sp.edges.size(); ++e) {
    const double edge0 = phase + sp.edges[e].azimuth;
    // delta(t) = edge angle - nail azimuth, continuous (unwrapped sample to sample).
    double t_prev = lo;
    double azimuth_prev = cached[0];
    double delta_prev = edge0 + omega * lo - azimuth_prev;
    for (int k = 1; k <= samples; ++k) {
      const double t = sample_time(k);
      if (best && t_prev >= best->time) break;
      const double azimuth = azimuth_at(k, azimuth_prev);
      const double delta = edge0 + omega * t - azimuth;
      const double turns_prev = std::floor(delta_prev / units::two_pi), turns = std::floor(delta / units::two_pi);
      if (turns != turns_prev) {
        // A multiple of 2 pi lies between: solve delta(t) = target by Newton's method kept
        // inside the bracket (bisecting when a step would leave it), converging in a few
        // steps where bisection took some forty. delta' = omega - (q x w) / |q|^2.
        const double target = units::two_pi * std::max(turns, turns_prev);
        double a_t = t_prev, b_t = t, a_d = delta_prev - target;
        const double b_d = delta - target;
        double ts = a_t - a_d * (b_t - a_t) / (b_d - a_d);  // the secant's root to start
        if (!(ts > a_t && ts < b_t)) ts = 0.5 * (a_t + b_t);
        for (int it = 0; it < 60; ++it) {
          const Eigen::Vector2d qm = q_at(ts);
          const double dm = edge0 + omega * ts - azimuth_near(ts, azimuth_prev) - target;
          if (dm == 0) break;
          if ((dm < 0) == (a_d < 0))
            a_t = ts, a_d = dm;
          else
            b_t = ts;
          const double slope = omega - (qm.x() * w.y() - qm.y() * w.x()) / std::max(qm.squaredNorm(), 1e-300);
          double next = ts - dm / slope;
          if (!(next > a_t && next < b_t)) next = 0.5 * (a_t + b_t);
          const bool converged = std::abs(next - ts) <= 1e-13 || b_t - a_t <= 1e-12;
          ts = next;
          if (converged) break;
        }
        if (!in_slab_at(ts)) {  // the turning nail lay clear of the slab as this edge passed
          t_prev = t, azimuth_prev = azimuth, delta_prev = delta;
          continue;
        }
        const Eigen::Vector2d qs = q_at(ts);
        const double r = qs.norm();
        // The edge meets the nail only if it is faster along its own motion there (a nail
        // that outruns the edge, as one just thrown by it does, is passed, not struck).
        const Eigen::Vector2d tangent = sp.sense * Eigen::Vector2d(-qs.y(), qs.x()) / std::max(r, 1e-12);
        const bool approaching = sp.omega() * r > w.dot(tangent);
        if (approaching && r > 0 && r <= sp.edges[e].reach && (!best || ts < best->time)) {
          BladeHit h;
          h.edge = e;
          h.time = ts;
          h.radius = r;
          h.azimuth = std::atan2(qs.y(), qs.x());
          best = h;
        }
        break;  // later crossings of this edge are later still
      }
      t_prev = t, azimuth_prev = azimuth, delta_prev = delta;
    }
  }
  return best;
}

std::optional<blade::ContactOutcome> strike(const Spindle& sp, const BladeHit& hit, const NailAtBlade& nail) {
  const Edge& edge = sp.edges[hit.edge];
  const auto where = edge.arm ? blade::locate(sp.blade, *edge.arm, hit.radius)
                              : std::optional<blade::ContactLocation>(blade::ContactLocation::hub(hit.radius));
  if (!where) return std::nullopt;
  // The edge moves along the tangent of its sense of rotation; its lift tilts the
  // contact normal up out of the blade plane.
  const double cos_lift = std::cos(sp.lift_angle), sin_lift = std::sin(sp.lift_angle);
  const blade::Vec3 tangent = sp.sense * blade::Vec3(-std::sin(hit.azimuth), std::cos(hit.azimuth), 0.0);
  blade::BladeAtContact at;
  at.normal = cos_lift * tangent + sin_lift * blade::Vec3::UnitZ();
  at.effective_mass = sp.model.effective_mass(*where) / (cos_lift * cos_lift);
  at.speed = sp.omega() * hit.radius * cos_lift;

  blade::StruckObject body;
  body.mass = nail.mass;
  body.velocity = nail.velocity;
  body.spin = nail.spin;
  blade::Rod rod;
  rod.length = nail.length;
  rod.transverse_inertia = nail.mass * nail.length * nail.length / 12.0;
  rod.axis = nail.axis;
  rod.offset = nail.offset;
  body.rod = rod;
  const blade::ContactOutcome contact = blade::resolve_contact(at, body, sp.restitution);
  if (!contact.approaching) return std::nullopt;
  return contact;
}

}  // namespace j232::feed
