#include "strike/contact_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "units/quantity.hpp"

namespace j232::strike {

Vec3 Motion::axis(double t) const { return turning().at(t - t0); }

Turning::Turning(const Vec3& axis, const Vec3& spin) : start(axis), along(axis), rate(spin.norm()) {
  if (!(rate > 0)) return;
  const Vec3 k = spin / rate;
  along = k * k.dot(axis);
  across = axis - along;
  ortho = k.cross(axis);
}

Vec3 turned(const Vec3& axis, const Vec3& spin, double dt) { return Turning(axis, spin).at(dt); }

// atan2 to within kCoarseAtan2Error rad (Abramowitz and Stegun 4.4.49, |error| <= 1e-5
// on [-1, 1]), a fifth the cost of the library's: the search only needs the nail's
// azimuth to bound how long an arm takes to reach it, and widens its window by the error.
double coarse_atan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  if (ax == 0 && ay == 0) return 0.0;
  const bool steep = ay > ax;
  const double z = steep ? ax / ay : ay / ax, z2 = z * z;
  double a = z * (0.9998660 + z2 * (-0.3302995 + z2 * (0.1801410 + z2 * (-0.0851330 + z2 * 0.0208351))));
  if (steep) a = 0.5 * units::pi - a;
  if (x < 0) a = units::pi - a;
  return y < 0 ? -a : a;
}

namespace {

// Time for a gap closing at speed v0 with acceleration up to a to close: v0 s + a s^2 / 2 = gap.
double time_to_close(double gap, double v0, double a) {
  if (a <= 1e-12) return v0 > 0 ? gap / v0 : HUGE_VAL;
  return (-v0 + std::sqrt(v0 * v0 + 2 * a * gap)) / a;
}

// An angle at least asin(x) (the half-angle a reach x r subtends at radius r), cheaply:
// x / sqrt(1 - x^2) = tan(asin x) >= asin x; a right angle for a reach near the radius;
// every azimuth (pi) for a reach beyond it (a nail across the axis).
double half_angle(double x) { return x < 0.7 ? x / std::sqrt(1 - x * x) : x < 1 ? 0.5 * units::pi : units::pi; }

// How far a nail is from touching a turning blade at one instant, in lower bounds on the
// time it needs: to reach the slab of its section (height), the disc of an edge's reach
// (radius), and the angle an arm must still turn to bring its section within reach of it.
// The angle is from the arm forward to the nail's centre, in (-pi, pi]: the arm can touch
// the capsule only while the centre is less than alpha_f ahead of it or alpha_b behind.
// Angular steps are kept short enough that the nail stays beyond 3/4 of its radius.
struct Outlook {
  const Spindle& sp;
  double z_time = 0, r = 0, vh = 0, accel_h = 0, azimuth = 0, alpha_f = 0, alpha_b = 0, cap = 0, rate = 0, overtake = 0, rho = 0,
         turned = 0;

  Outlook(const Spindle& spindle, double phase, const Motion& m, double reach_of_nail, const Vec3& c, const Vec3& v, double t)
      : sp(spindle), rho(reach_of_nail) {
    const BladeSection& sec = sp.section;
    const double qx = c.x() - sp.centre.x(), qy = c.y() - sp.centre.y(), z = c.z() - sp.height;
    r = std::sqrt(qx * qx + qy * qy), vh = std::sqrt(v.x() * v.x() + v.y() * v.y());
    accel_h = std::sqrt(m.a.x() * m.a.x() + m.a.y() * m.a.y());
    const double gap_z = std::max(z - rho - sec.top(), sec.bottom() - z - rho);
    z_time = gap_z > 0 ? time_to_close(gap_z, std::abs(v.z()), m.a.norm()) : 0.0;
    cap = time_to_close(0.25 * r, vh, accel_h);
    const double r_low = 0.75 * r;
    alpha_f = half_angle((rho + 1e-4) / r_low) + kCoarseAtan2Error;
    alpha_b = half_angle((rho - sec.back() + 1e-4) / r_low) + kCoarseAtan2Error;
    const double nail_rate = (vh + accel_h * std::min(cap, 1.0)) / std::max(r_low, 1e-9);
    rate = sp.omega() + nail_rate;
    overtake = nail_rate - sp.omega();
    azimuth = coarse_atan2(qy, qx);
    turned = phase + sp.sense * sp.omega() * t;
  }
  // The lower bound for edge e (0: it may touch now).
  double far(std::size_t e) const {
    double f = z_time;
    const double gap_r = r - rho - sp.edges[e].reach;
    if (gap_r > 0) f = std::max(f, time_to_close(gap_r, vh, accel_h));
    double ahead = sp.sense * (azimuth - turned - sp.edges[e].azimuth);
    ahead -= units::two_pi * std::nearbyint(ahead / units::two_pi);
    if (ahead > alpha_f || ahead < -alpha_b) {
      // The arm closes on the window from its front at no more than `rate`; the nail can
      // reach it from behind only by turning about the spindle faster than the arm (near
      // the axis), at no more than `overtake`.
      const double front = ahead > alpha_f ? ahead - alpha_f : ahead + units::two_pi - alpha_f;
      const double behind = ahead > alpha_f ? units::two_pi - alpha_b - ahead : -alpha_b - ahead;
      const double time = std::min(front / rate, overtake > 0 ? behind / overtake : HUGE_VAL);
      f = std::max(f, std::min(time, cap));
    }
    return f;
  }
};

// The least, over a segment, of the larger of two gaps that vary linearly along it (x and
// l at its ends a and b): how far its nearest point is from the wedge where both are <= 0.
double wedge_clearance(double x_a, double l_a, double x_b, double l_b) {
  double least = std::min(std::max(x_a, l_a), std::max(x_b, l_b));
  const double da = x_a - l_a, db = x_b - l_b;
  if ((da > 0) != (db > 0)) {  // the two gaps are equal within the segment
    const double s = da / (da - db);
    least = std::min(least, x_a + s * (x_b - x_a));
  }
  return least;
}

// The capsule against one edge's section at one instant.
struct Probe {
  double distance = 0;  // capsule surface to section, m (< 0: overlapping)
  SectionApproach approach;               // the nearest part's
  std::array<SectionApproach, 2> parts;   // each part's (plate, sail)
  Vec3 radial, forward, centre, axis, a3, b3;  // a3-b3: the part of the core over the arm
  bool off_arm = false;                       // no part of it is
  bool a_at_tip = false, b_at_tip = false;    // that end cut at the tip radius
  Vec2 whole_a = Vec2::Zero(), whole_b = Vec2::Zero();  // the whole core in the section's plane
};

class EdgeSearch {
 public:
  EdgeSearch(const Spindle& sp, std::size_t e, double phase, const projectile::Projectile& nail, const Motion& m)
      : sp_(sp), e_(e), phase_(phase), m_(m), turning_(m.turning()), hs_(nail.half_segment()), rad_(nail.radius()), rho_(hs_ + rad_) {}

  std::optional<Contact> run(double t1, SearchStats& stats) {
    const double omega = sp_.omega(), spin_rate = m_.spin.norm();
    double t = m_.t0, t_safe = m_.t0;
    bool known_apart = false;  // at t_safe the capsule overlapped the section by less than the tolerance
    double d_safe = HUGE_VAL;  // the distance there, when a probe measured it (else HUGE_VAL)
    int shrinking = 0;         // window steps in a row each shorter than the one before
    double last_far = HUGE_VAL;
    for (int step = 0; step < kMaxSearchSteps; ++step, ++stats.steps) {
      if (t > t1) return std::nullopt;
      const Vec3 c = m_.centre(t), v = m_.velocity(t);
      const Outlook look(sp_, phase_, m_, rho_, c, v, t);
      const double far = look.far(e_);
      if (far > t1 - t) return std::nullopt;
      if (far > 0) {
        // The window's bounds assume the arm closes at its full rate. A body turning with the
        // arm (a stone the knife just pushed, moving at the knife's speed just ahead of it)
        // closes far slower, so each step ends short of the window by nearly what it began,
        // and the steps shrink geometrically without end (by a factor as near 1 as the arm is
        // slow to gain on it, so at any scale). After kStallSteps window steps in a row, each
        // shorter than the one before, the exact distance's step is taken too, as the probe
        // path takes it (a lower bound on the time to a touch but for its kMinStep floor, or
        // the off-arm step's floor of 1/64 of the window; a step landing in the section is
        // bisected back from t_safe as there).
        double ahead = std::max(far, 1e-10);
        d_safe = HUGE_VAL;
        shrinking = far < last_far ? shrinking + 1 : 0;
        last_far = far;
        // The same stall comes at the radial bound: a nail passing the tip circle nearly along
        // it closes that gap far slower than its whole speed, the bound's rate. Either way the
        // probe may find it wholly beyond the tip, and then it takes the off-arm step.
        if (shrinking >= kStallSteps) {
          const Probe p = probe(t);
          if (p.off_arm)
            ahead = std::max(ahead, off_arm_step(p, v, look));
          else if (p.distance > kContactTolerance)
            ahead = std::max(ahead, clear_step(p, c, v)), d_safe = p.distance;
        }
        t_safe = t, known_apart = true;
        t += ahead;
        continue;
      }
      shrinking = 0, last_far = HUGE_VAL;
      // Near the arm: the distance between the capsule and the section.
      Probe p = probe(t);
      if (p.off_arm) {
        t_safe = t, known_apart = true, d_safe = HUGE_VAL;
        t += off_arm_step(p, v, look);
        continue;
      }
      if (p.distance > kContactTolerance) {
        t_safe = t, known_apart = true, d_safe = p.distance;
        t += clear_step(p, c, v);
        continue;
      }
      if (p.distance < -kContactTolerance && known_apart) {
        // Stepped into the blade (a bound that did not hold, or sliding along a face while
        // parting elsewhere): back to the touch by regula falsi (Illinois) on the distance,
        // which is nearly linear in time over a step, or by halves where a probe is off the
        // arm or was not measured.
        double lo = t_safe, hi = t, d_lo = d_safe, d_hi = p.distance;
        int side = 0;
        for (int it = 0; it < 60 && hi - lo > 1e-13; ++it) {
          double mid = d_lo < HUGE_VAL ? (lo * d_hi - hi * d_lo) / (d_hi - d_lo) : 0.5 * (lo + hi);
          if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
          Probe pm = probe(mid);
          if (pm.off_arm || pm.distance > kContactTolerance) {
            lo = mid, d_lo = pm.off_arm ? HUGE_VAL : pm.distance;
            if (side == -1) d_hi *= 0.5;
            side = -1;
          } else {
            hi = mid, p = pm;
            if (pm.distance >= -kContactTolerance) break;  // within the tolerance of the touch
            d_hi = pm.distance;
            if (side == 1 && d_lo < HUGE_VAL) d_lo *= 0.5;
            side = 1;
          }
        }
        t = hi;
      }
      // Touching (or overlapping where the search began): a contact if the points approach.
      const Touch touch = touch_at(t, p);
      // (At the search's start, where the last impulse may have left the points barely
      // parting or at rest, only a touch that really approaches counts: no zero-time repeat.)
      const bool real = t > m_.t0 || -touch.v_rel.dot(touch.contact.normal) > kSameInstantApproach;
      if (touch.approaching && real) return touch.contact;
      const Vec3& v_rel = touch.v_rel;
      // Parting: step on (a step that goes deeper is bisected back), or, overlapping where
      // the search began, by the overlap.
      const double bound = v_rel.norm() + (omega + spin_rate) * hs_ + 1e-9;
      t_safe = t, known_apart = p.distance >= -kContactTolerance, d_safe = HUGE_VAL;
      t += (std::max(-p.distance, 0.0) + kMinStep) / bound;
    }
    stats.gave_up = true;
    return std::nullopt;
  }

  // A step from a probe `p` that found the capsule wholly beyond the tip (or behind the axis),
  // its centre moving at v: its ends must cross the tip radius first, which they do no faster
  // than this. A nail hovering at the tip radius is looked at 64 times a pass (a step into
  // the plate is bisected back).
  double off_arm_step(const Probe& p, const Vec3& v, const Outlook& look) const {
    const double omega = sp_.omega();
    const double radial_rate = v.norm() + m_.spin.norm() * hs_ + omega * (rho_ - sp_.section.back()) + 1e-9;
    return std::max(p.distance / radial_rate, (look.alpha_f + look.alpha_b) / (64 * omega));
  }

  // A step the capsule, clear of the section by more than the tolerance at the probe `p` (its
  // centre c moving at v), surely takes before touching it (to within kMinStep: a step that
  // lands in the plate is bisected back).
  double clear_step(const Probe& p, const Vec3& c, const Vec3& v) const {
    const BladeSection& sec = sp_.section;
    const Vec3 C(sp_.centre.x(), sp_.centre.y(), sp_.height);
    const double omega = sp_.omega(), spin_rate = m_.spin.norm(), accel = m_.a.norm();
    // The line through the section's nearest point, across the normal, separates the
    // two (the section is convex): the core's distance past it is a lower bound on the
    // distance, and it shrinks no faster than the centre's motion toward it (in the
    // blade's frame, projected on the section) plus the turn of the core about its
    // centre, (spin + omega) half-length, plus the curvature of the centre's path in
    // the turning frame. Steps are at least kMinStep of that: one that lands in the
    // plate is bisected back to the touch, and a touch that began and ended within one
    // is shallower than that.
    const Vec3 q(c.x() - C.x(), c.y() - C.y(), 0.0);
    const double x_c = q.dot(p.radial), u_c = q.dot(p.forward);
    const double u_rate = v.dot(p.forward) - omega * x_c, w_rate = v.z();
    const double c2 = accel + 2 * omega * std::sqrt(v.x() * v.x() + v.y() * v.y()) + omega * omega * (std::abs(u_c) + hs_);
    // Each part of the section (plate, sail) has its own separating line: the step is
    // the least any of them allows.
    double step_time = HUGE_VAL;
    const auto bound_by = [&](const SectionApproach& part) {
      const double toward = -(part.normal.x() * u_rate + part.normal.y() * w_rate);
      const double c1 = std::max(toward, 0.0) + (omega + spin_rate) * hs_ + 1e-9;
      const double gap = std::max(part.distance - rad_, kMinStep);
      step_time = std::min(step_time, 2 * gap / (c1 + std::sqrt(c1 * c1 + 2 * c2 * gap)));
    };
    for (int k = 0; k < sec.parts(); ++k) bound_by(p.parts[static_cast<std::size_t>(k)]);
    // A core reaching beyond the tip: its outer part may come over the arm within the
    // step. The arm lies within the wedge behind both the part's separating line and
    // the tip's plane (x <= reach), so no point of the core can reach it before it has
    // closed the larger of its two gaps to them; each gap closes no faster than the
    // point's motion along that line's normal (for the tip's plane, radially in the
    // blade's frame: v . radial + omega u) plus the core's turn, and the centre's path
    // curves at most as much as the section's case allows with the radius for u.
    if (p.a_at_tip || p.b_at_tip) {
      const double radial_rate = v.dot(p.radial) + omega * u_c;
      const double r = std::sqrt(q.x() * q.x() + q.y() * q.y());
      const double c2_wedge = accel + 2 * omega * std::sqrt(v.x() * v.x() + v.y() * v.y()) + omega * omega * (r + hs_);
      const Vec3 end_a = p.centre - hs_ * p.axis, end_b = p.centre + hs_ * p.axis;
      const double reach = sp_.edges[e_].reach;
      const double x_a = (end_a - C).dot(p.radial) - reach, x_b = (end_b - C).dot(p.radial) - reach;
      for (int k = 0; k < sec.parts(); ++k) {
        const SectionApproach& part = p.parts[static_cast<std::size_t>(k)];
        const double l_a = part.normal.dot(p.whole_a - part.on_section), l_b = part.normal.dot(p.whole_b - part.on_section);
        const double gap = std::max(wedge_clearance(x_a, l_a, x_b, l_b) - rad_, kMinStep);
        const double toward = std::max({-(part.normal.x() * u_rate + part.normal.y() * w_rate), -radial_rate, 0.0});
        const double c1 = toward + (omega + spin_rate) * hs_ + 1e-9;
        step_time = std::min(step_time, 2 * gap / (c1 + std::sqrt(c1 * c1 + 2 * c2_wedge * gap)));
      }
    }
    // The ends' own clearances, to second order, allow far longer steps to a nail that
    // tumbles fast (spin x half-length is a loose bound on how fast its ends close on
    // the plate when they swing across the normal).
    step_time = std::max(step_time, ends_step(p, c, v, omega, spin_rate, accel));
    return step_time;
  }

 public:
  struct Touch {
    Contact contact;
    Vec3 v_rel = Vec3::Zero();
    bool approaching = false;
  };
  // The contact the probe at t describes (the capsule touching the section).
  Touch touch_at(double t, const Probe& p) const {
    const Vec3 C(sp_.centre.x(), sp_.centre.y(), sp_.height);
    const BladeSection& sec = sp_.section;
    Touch out;
    // The core reaching into the section across the tip radius meets the arm's end face.
    // (Overlapping with an end cut at the tip radius: the core came in across the tip.)
    const bool separable = p.approach.distance > 0;
    const bool at_tip = !separable && (p.a_at_tip || p.b_at_tip);
    const Vec3 normal = separable ? Vec3(p.approach.normal.x() * p.forward + p.approach.normal.y() * Vec3::UnitZ())
                        : at_tip  ? Vec3(p.radial)
                                  : Vec3(p.forward);  // core inside the plate: pushed along the motion
    const Vec3 on_core = at_tip ? (p.a_at_tip ? p.a3 : p.b3) : Vec3(p.a3 + p.approach.s * (p.b3 - p.a3));
    const Vec3 point = at_tip ? on_core : Vec3(on_core - rad_ * normal);
    out.v_rel = m_.velocity(t) + m_.spin.cross(point - p.centre) - sp_.velocity_at(point);
    // A touch is the capsule's surface reaching the section (or the core reaching it across
    // the tip radius, the arm's end face). A core already inside the plate came in across
    // the spindle's axis, where the arm goes on into the hub or the other arm and no face
    // is modelled: the hub's region is left transparent rather than given a made-up face.
    out.approaching = out.v_rel.dot(normal) < 0 && (separable || at_tip);
    Contact& k = out.contact;
    k.edge = e_;
    k.time = t;
    k.centre = p.centre;
    k.axis = p.axis;
    k.point = point;
    k.normal = normal;
    // On the arm: the core's part over it touches (the surface point may stand up to a
    // radius beyond the tip).
    k.radius = std::clamp((on_core - C).dot(p.radial), 0.0, sp_.edges[e_].reach);
    k.forward_offset = p.approach.on_section.x();
    k.radial = p.radial;
    k.forward = p.forward;
    k.part = p.approach.on_section.x() < -sec.shape().width ? 1 : 0;
    return out;
  }

  // A safe step from the whole core's two ends against each part's separating line (the
  // line through the part's nearest point, across the normal; the part lies behind it).
  // An end's clearance f from that line moves smoothly in the blade's frame: f' is the
  // end's velocity there along the normal (exact), and |f''| is at most its acceleration
  // there, M = |a| + w^2 h + 2 W (v_h + w h) + W^2 |u| (the centre's acceleration, the
  // end's turn about the centre at spin w, the Coriolis and centripetal terms of the
  // blade's turn W, u the end's distance along the blade's motion), bounded over at most
  // kCap. The first root of f + f' s - M s^2 / 2 is a step in which no end crosses the
  // line. None (0) when the line does not separate the whole core (part of it is beyond
  // the arm's tip).
  double ends_step(const Probe& p, const Vec3& c, const Vec3& v, double omega, double w, double accel) const {
    constexpr double kCap = 2e-4;  // s
    const Vec3 C(sp_.centre.x(), sp_.centre.y(), sp_.height);
    const double h = hs_, qx = c.x() - C.x(), qy = c.y() - C.y();
    const double r = std::sqrt(qx * qx + qy * qy), vh = std::sqrt(v.x() * v.x() + v.y() * v.y()) + accel * kCap;
    const double u_max = r + h + (vh + w * h + omega * (r + h)) * kCap;
    const double M = accel + w * w * h + 2 * omega * (vh + w * h) + omega * omega * u_max + 1e-9;
    double step = kCap;
    for (const double sign : {-1.0, 1.0}) {
      const Vec3 arm = sign * h * p.axis, end = c + arm, v_end = v + m_.spin.cross(arm);
      const Vec2 at((end - C).dot(p.forward), end.z() - C.z());
      const Vec2 rate(v_end.dot(p.forward) - omega * (end - C).dot(p.radial), v_end.z());
      for (int k = 0; k < sp_.section.parts(); ++k) {
        const SectionApproach& part = p.parts[static_cast<std::size_t>(k)];
        const double f = part.normal.dot(at - part.on_section) - rad_;
        if (!(f > 0)) return 0.0;
        const double gap = std::max(f, kMinStep), df = part.normal.dot(rate);
        const double root = std::sqrt(df * df + 2 * M * gap);
        step = std::min(step, df >= 0 ? (df + root) / M : 2 * gap / (root - df));
      }
    }
    return step;
  }

  Probe probe(double t) const {
    Probe p;
    sp_.frame(e_, phase_, t, p.radial, p.forward);
    p.centre = m_.centre(t);
    p.axis = turning_.at(t - m_.t0);
    p.a3 = p.centre - hs_ * p.axis;
    p.b3 = p.centre + hs_ * p.axis;
    const Vec3 C(sp_.centre.x(), sp_.centre.y(), sp_.height);
    p.whole_a = Vec2((p.a3 - C).dot(p.forward), p.a3.z() - C.z());
    p.whole_b = Vec2((p.b3 - C).dot(p.forward), p.b3.z() - C.z());
    // Only the part of the core over the arm (from the axis out to its tip) can touch it.
    const double xa = (p.a3 - C).dot(p.radial), xb = (p.b3 - C).dot(p.radial), reach = sp_.edges[e_].reach;
    if (std::max(xa, xb) < 0 || std::min(xa, xb) > reach) {
      // Off the arm: no touch; the core's radial gap to it bounds the step.
      p.distance = std::min(std::abs(xa - std::clamp(xa, 0.0, reach)), std::abs(xb - std::clamp(xb, 0.0, reach)));
      p.off_arm = true;
      return p;
    }
    if (xa != xb) {
      const double s0 = std::clamp((0.0 - xa) / (xb - xa), 0.0, 1.0), s1 = std::clamp((reach - xa) / (xb - xa), 0.0, 1.0);
      const double lo = std::min(s0, s1), hi = std::max(s0, s1);
      p.a_at_tip = lo > 0 && xa > reach;
      p.b_at_tip = hi < 1 && xb > reach;
      const Vec3 a = p.a3 + lo * (p.b3 - p.a3), b = p.a3 + hi * (p.b3 - p.a3);
      p.a3 = a, p.b3 = b;
    }
    const Vec2 a((p.a3 - C).dot(p.forward), p.a3.z() - C.z()), b((p.b3 - C).dot(p.forward), p.b3.z() - C.z());
    for (int k = 0; k < sp_.section.parts(); ++k) {
      p.parts[static_cast<std::size_t>(k)] = segment_to_polygon(a, b, sp_.section.part(k));
      if (k == 0 || p.parts[static_cast<std::size_t>(k)].distance < p.approach.distance) p.approach = p.parts[static_cast<std::size_t>(k)];
    }
    p.distance = p.approach.distance - rad_;
    return p;
  }

 private:
  const Spindle& sp_;
  std::size_t e_;
  double phase_;
  const Motion& m_;
  Turning turning_;
  double hs_, rad_, rho_;
};

}  // namespace

namespace {

// The reference: near an arm, fixed steps of at most kReferenceStep of relative motion, the
// clearance of every edge tested at each; the first approaching touch is refined by
// bisection. Away from every arm's plate (a plain distance in plan to its rectangle, or
// the height above or below it) the step is that gap over the fastest relative motion.
constexpr double kReferenceStep = 1e-5;  // m

std::optional<Contact> fixed_step_contact(const Spindle& sp, double phase, const projectile::Projectile& nail, const Motion& m, double t1,
                                          SearchStats& stats) {
  const double rho = nail.half_segment() + nail.radius();
  const double bound = m.v0.norm() + m.a.norm() * (t1 - m.t0) + sp.omega() * (sp.reach + rho) + m.spin.norm() * nail.half_segment();
  const double dt = kReferenceStep / std::max(bound, 1e-9);
  std::vector<EdgeSearch> edges;
  for (std::size_t e = 0; e < sp.edges.size(); ++e) edges.emplace_back(sp, e, phase, nail, m);
  std::vector<double> before(sp.edges.size(), HUGE_VAL);
  const Vec3 C(sp.centre.x(), sp.centre.y(), sp.height);
  double step = dt;
  for (double t = m.t0; t <= t1; t += step) {
    ++stats.steps;
    // Far from every arm's plate (in plan, or above or below it) the step is that gap over
    // the fastest any point of either body moves; near it, dt.
    const Vec3 c = m.centre(t);
    const double z = c.z() - sp.height;
    double gap = std::max(z - rho - sp.section.top(), sp.section.bottom() - z - rho);
    double plan = HUGE_VAL;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      Vec3 radial, forward;
      sp.frame(e, phase, t, radial, forward);
      const double x = (c - C).dot(radial), u = (c - C).dot(forward);
      const double dx = x - std::clamp(x, 0.0, sp.edges[e].reach), du = u - std::clamp(u, sp.section.back(), 0.0);
      plan = std::min(plan, std::sqrt(dx * dx + du * du) - rho);
    }
    gap = std::max(gap, plan);
    if (gap > kReferenceStep) {
      std::fill(before.begin(), before.end(), HUGE_VAL);
      step = std::max(dt, gap / bound);
      continue;
    }
    step = dt;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto p = edges[e].probe(t);
      const double d = p.off_arm ? HUGE_VAL : p.distance;
      if (d <= kContactTolerance && before[e] > kContactTolerance) {
        double lo = t - step, hi = t;
        for (int it = 0; it < 60 && hi - lo > 1e-13; ++it) {
          const double mid = 0.5 * (lo + hi);
          const auto pm = edges[e].probe(mid);
          (!pm.off_arm && pm.distance <= kContactTolerance ? hi : lo) = mid;
        }
        const auto touch = edges[e].touch_at(hi, edges[e].probe(hi));
        if (touch.approaching) return touch.contact;
      }
      before[e] = d;
    }
  }
  return std::nullopt;
}

}  // namespace

Clearance clearance(const Spindle& spindle, std::size_t e, double phase, const projectile::Projectile& nail, const Motion& motion, double t) {
  const EdgeSearch search(spindle, e, phase, nail, motion);
  const auto p = search.probe(t);
  Clearance c;
  c.distance = p.distance;
  c.off_arm = p.off_arm;
  if (!p.off_arm) c.approaching = search.touch_at(t, p).approaching;
  return c;
}

std::optional<Contact> first_contact(const Spindle& spindle, double phase, const projectile::Projectile& nail, const Motion& motion,
                                     double t1, SearchStats& stats, SearchMethod method) {
  std::optional<Contact> best;
  // The whole blade first: a nail that cannot reach its slab or its disc in time is not
  // looked at edge by edge.
  const Vec3& c = motion.p0;
  const Vec3& v = motion.v0;
  const double rho = nail.half_segment() + nail.radius(), accel = motion.a.norm();
  const double gap_z = std::max(c.z() - spindle.height - rho - spindle.section.top(), spindle.height + spindle.section.bottom() - c.z() - rho);
  if (gap_z > 0 && time_to_close(gap_z, std::abs(v.z()), accel) > t1 - motion.t0) return best;
  const double dx = c.x() - spindle.centre.x(), dy = c.y() - spindle.centre.y();
  const double r = std::sqrt(dx * dx + dy * dy);
  if (r - rho > spindle.reach && time_to_close(r - rho - spindle.reach, std::sqrt(v.x() * v.x() + v.y() * v.y()), accel) > t1 - motion.t0)
    return best;
  if (method == SearchMethod::FixedSteps) return fixed_step_contact(spindle, phase, nail, motion, t1, stats);
  // The whole blade's disc once more, over the centre's path in plan: every point of an arm
  // lies within hypot(reach, back) of the axis (radially out to its reach, its section behind
  // the leading edge back to `back`), and the centre's path in plan is its straight line from
  // p0 at v0 within |a_h| T^2 / 2 of it. A nail riding round the skirt outside the tip circle
  // moves across the radius, not along it, so the bound on the time to close above (at its
  // whole horizontal speed) does not rule it out.
  {
    const double T = t1 - motion.t0;
    const Eigen::Vector2d q(dx, dy), w(v.x() * T, v.y() * T);
    const double ww = w.squaredNorm();
    const double s = ww > 0 ? std::clamp(-q.dot(w) / ww, 0.0, 1.0) : 0.0;
    const double a_h = std::sqrt(motion.a.x() * motion.a.x() + motion.a.y() * motion.a.y());
    const double nearest = (q + s * w).norm() - 0.5 * a_h * T * T;
    if (nearest - rho > std::hypot(spindle.reach, spindle.section.back()) + 10 * kContactTolerance) return best;
  }
  // Then each edge's outlook from the start, worked out once for them all.
  const Outlook look(spindle, phase, motion, rho, c, v, motion.t0);
  for (std::size_t e = 0; e < spindle.edges.size(); ++e) {
    ++stats.steps;
    if (look.far(e) > (best ? best->time : t1) - motion.t0) continue;
    auto found = EdgeSearch(spindle, e, phase, nail, motion).run(best ? best->time : t1, stats);
    if (found && (!best || found->time < best->time)) best = found;
  }
  return best;
}

}  // namespace j232::strike
