#include "flight/flight_audit.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "flight/face_touch.hpp"
#include "scene/capsule_audit.hpp"

// The face search gives up before renewed slacks could take a capsule past what the audit allows.
static_assert(j232::flight::kDeepestSink + j232::flight::kLeavingSlack <= j232::flight::kAuditOverlap * (1 + 1e-12));

namespace j232::flight {

void FlightAudit::merge(const FlightAudit& o) {
  poses += o.poses;
  if (o.deepest > deepest) deepest = o.deepest, deepest_time = o.deepest_time, deepest_face = o.deepest_face, deepest_label = o.deepest_label;
  energy_gains += o.energy_gains;
  largest_gain = std::max(largest_gain, o.largest_gain);
  placed_depth = std::max(placed_depth, o.placed_depth);
}

FlightAudit audit_flight(const scene::Soup& soup, const projectile::Projectile& nail, const std::vector<FlightStretch>& stretches,
                         const std::vector<FlightEvent>& events, int samples, bool as_placed) {
  FlightAudit a;
  // Curtains the nail went through: it is inside their links from then on, until clear (not
  // an overlap with steel). Every guard passed at or before a pose is left out for it.
  const auto passing = [&](double t) {
    int guard = -1;
    for (const auto& e : events)
      if (e.kind == FlightEvent::Kind::GuardPass && e.time <= t) guard = e.guard;
    return guard;
  };
  scene::Allowances placed;
  if (as_placed && !stretches.empty()) {
    const strike::Motion& m = stretches.front().motion;
    const double dt = stretches.front().from - m.t0, w = m.spin.norm();
    const Vec3 centre = m.p0 + m.v0 * dt + 0.5 * dt * dt * m.a;
    const Vec3 axis = w > 0 ? Vec3(Eigen::AngleAxisd(w * dt, m.spin / w) * m.axis0) : m.axis0;
    placed = scene::overlaps(soup, centre, axis.normalized(), nail.half_segment(), nail.radius());
    double soil = 0;
    for (auto& p : placed) {
      a.placed_depth = std::max(a.placed_depth, p.second);
      if (soup.labels[p.first] == scene::Surface::Ground) soil = std::max(soil, p.second), p.second = 0;
      p.second += kLeavingSlack;
    }
    if (soil > 0) placed.emplace_back(scene::kAnyGround, soil + kLeavingSlack);
  }
  for (const auto& s : stretches) {
    const strike::Motion& m = s.motion;
    const double w = m.spin.norm();
    for (int k = 0; k <= samples + 1; ++k) {
      const double t = s.from + (s.until - s.from) * k / (samples + 1);
      const double dt = t - m.t0;
      // The pose by its own formulas: the centre's parabola, the axis turned about the spin.
      const Vec3 centre = m.p0 + m.v0 * dt + 0.5 * dt * dt * m.a;
      const Vec3 axis = w > 0 ? Vec3(Eigen::AngleAxisd(w * dt, m.spin / w) * m.axis0) : m.axis0;
      const scene::Overlap o = scene::deepest_overlap(soup, centre, axis.normalized(), nail.half_segment(), nail.radius(), passing(t),
                                                      placed.empty() ? nullptr : &placed);
      ++a.poses;
      if (o.depth > a.deepest) a.deepest = o.depth, a.deepest_time = t, a.deepest_face = o.face, a.deepest_label = o.label;
    }
  }
  for (const auto& e : events) {
    if (e.kind != FlightEvent::Kind::Bounce && e.kind != FlightEvent::Kind::Slide) continue;
    const double gain = e.energy_after - e.energy_before;
    if (gain > 1e-9 * std::max(1e-3, std::abs(e.energy_before))) ++a.energy_gains, a.largest_gain = std::max(a.largest_gain, gain);
  }
  return a;
}

}  // namespace j232::flight
