#include "strike/blade_section.hpp"

#include <algorithm>
#include <cmath>

namespace j232::strike {

namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Parameter of the point of segment p-q nearest x, in [0, 1].
double nearest_on(const Vec2& p, const Vec2& q, const Vec2& x) {
  const Vec2 d = q - p;
  const double l2 = d.squaredNorm();
  return l2 > 0 ? std::clamp((x - p).dot(d) / l2, 0.0, 1.0) : 0.0;
}

bool inside(const ConvexPolygon& poly, const Vec2& x) {
  for (int i = 0; i < poly.n; ++i) {
    const Vec2& p = poly.v[static_cast<std::size_t>(i)];
    const Vec2& q = poly.v[static_cast<std::size_t>((i + 1) % poly.n)];
    if (cross(q - p, x - p) < 0) return false;
  }
  return true;
}

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& p, const Vec2& q) {
  const double d1 = cross(b - a, p - a), d2 = cross(b - a, q - a), d3 = cross(q - p, a - p), d4 = cross(q - p, b - p);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

}  // namespace

SectionApproach segment_to_polygon(const Vec2& a, const Vec2& b, const ConvexPolygon& poly) {
  SectionApproach best;
  // Overlap (an end inside, or the segment crossing an edge) is possible only where the
  // bounding boxes overlap.
  const auto overlap = [&](double s) {
    best.distance = 0;
    best.s = s;
    best.on_section = a + s * (b - a);
    return best;
  };
  const bool boxes_meet = std::min(a.x(), b.x()) <= poly.hi.x() && std::max(a.x(), b.x()) >= poly.lo.x() &&
                          std::min(a.y(), b.y()) <= poly.hi.y() && std::max(a.y(), b.y()) >= poly.lo.y();
  if (boxes_meet) {
    if (inside(poly, a)) return overlap(0);
    if (inside(poly, b)) return overlap(1);
    for (int i = 0; i < poly.n; ++i) {
      const Vec2& p = poly.v[static_cast<std::size_t>(i)];
      const Vec2& q = poly.v[static_cast<std::size_t>((i + 1) % poly.n)];
      if (segments_cross(a, b, p, q)) return overlap(std::clamp(cross(q - p, p - a) / cross(q - p, b - a), 0.0, 1.0));
    }
  }
  // Apart: the nearest pair has an end of the segment or a vertex of the polygon in it.
  // Squared distances, one root at the end.
  double best2 = HUGE_VAL;
  const Vec2 d = b - a;
  const double dl2 = d.squaredNorm();
  for (int i = 0; i < poly.n; ++i) {
    const Vec2& p = poly.v[static_cast<std::size_t>(i)];
    const Vec2& q = poly.v[static_cast<std::size_t>((i + 1) % poly.n)];
    const auto consider = [&](double s, const Vec2& on_poly) {
      const double dist2 = (a + s * d - on_poly).squaredNorm();
      if (dist2 < best2) best2 = dist2, best.s = s, best.on_section = on_poly;
    };
    consider(0, p + nearest_on(p, q, a) * (q - p));
    consider(1, p + nearest_on(p, q, b) * (q - p));
    consider(nearest_on(a, b, p), p);
    // A segment lying parallel to an edge touches it along an interval: its middle.
    const Vec2 e = q - p;
    const double el2 = e.squaredNorm(), c = cross(d, e);
    if (el2 > 0 && dl2 > 0 && c * c <= 1e-18 * el2 * dl2) {
      const double el = std::sqrt(el2);
      const Vec2 t = e / el;
      const double sa = (a - p).dot(t), sb = (b - p).dot(t);
      const double lo = std::max(0.0, std::min(sa, sb)), hi = std::min(el, std::max(sa, sb));
      if (hi > lo) {
        const Vec2 mid = p + 0.5 * (lo + hi) * t;
        const double s = std::clamp((mid - a).dot(d) / dl2, 0.0, 1.0);
        const double dist2 = (a + s * d - mid).squaredNorm();
        if (dist2 <= best2 * (1 + 1e-12)) best2 = dist2, best.s = s, best.on_section = mid;
      }
    }
  }
  best.distance = std::sqrt(best2);
  if (best.distance > 0) best.normal = (a + best.s * d - best.on_section) / best.distance;
  return best;
}

BladeSection::BladeSection(const EdgeShape& shape) : shape_(shape) {
  const double t = shape.thickness, half = 0.5 * t, w = shape.width;
  // The bevel's run back from the edge (none for a square edge), at most the width.
  const double run = std::min(w, shape.bevel_angle >= 0.5 * 3.141592653589793 - 1e-12 ? 0.0 : t / std::tan(shape.bevel_angle));
  ConvexPolygon plate;
  plate.n = 4;
  if (shape.bevel_on_top)
    plate.v = {Vec2(-w, -half), Vec2(0, -half), Vec2(-run, half), Vec2(-w, half)};
  else
    plate.v = {Vec2(-w, -half), Vec2(-run, -half), Vec2(0, half), Vec2(-w, half)};
  if (run == 0) plate.v = {Vec2(-w, -half), Vec2(0, -half), Vec2(0, half), Vec2(-w, half)};
  parts_[0] = plate;
  count_ = 1;
  const auto box = [](ConvexPolygon& p) {
    p.lo = p.hi = p.v[0];
    for (int i = 1; i < p.n; ++i) p.lo = p.lo.cwiseMin(p.v[static_cast<std::size_t>(i)]), p.hi = p.hi.cwiseMax(p.v[static_cast<std::size_t>(i)]);
  };
  box(parts_[0]);
  back_ = -w;
  top_ = half;
  if (shape.sail_height > 0) {
    // The trailing strip, of the plate's thickness, turned up behind the width.
    const double h = shape.sail_height, rise = h / std::tan(std::max(shape.sail_angle, 1e-3));
    ConvexPolygon sail;
    sail.n = 5;
    sail.v = {Vec2(-w - t, -half), Vec2(-w, -half), Vec2(-w, half), Vec2(-w - rise, half + h), Vec2(-w - rise - t, half + h)};
    parts_[1] = sail;
    box(parts_[1]);
    count_ = 2;
    back_ = -w - rise - t;
    top_ = half + h;
  }
}

SectionApproach BladeSection::approach(const Vec2& a, const Vec2& b) const {
  SectionApproach best = segment_to_polygon(a, b, parts_[0]);
  for (int k = 1; k < count_; ++k) {
    const SectionApproach other = segment_to_polygon(a, b, parts_[static_cast<std::size_t>(k)]);
    if (other.distance < best.distance) best = other;
  }
  return best;
}

}  // namespace j232::strike
