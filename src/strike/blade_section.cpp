#include "strike/blade_section.hpp"

#include <algorithm>
#include <cmath>

namespace j232::strike {

namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

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

void ConvexPolygon::finish() {
  lo = hi = v[0];
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    lo = lo.cwiseMin(v[k]), hi = hi.cwiseMax(v[k]);
    edge[k] = v[static_cast<std::size_t>((i + 1) % n)] - v[k];
    const double l2 = edge[k].squaredNorm();
    inv_len2[k] = l2 > 0 ? 1 / l2 : 0.0;
  }
}

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
  // Squared distances, one root at the end; the edges' inverse squared lengths are the
  // polygon's own, the segment's worked out once.
  double best2 = HUGE_VAL;
  const Vec2 d = b - a;
  const double dl2 = d.squaredNorm(), inv_dl2 = dl2 > 0 ? 1 / dl2 : 0.0;
  for (int i = 0; i < poly.n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Vec2& p = poly.v[k];
    const Vec2& e = poly.edge[k];
    const double inv_el2 = poly.inv_len2[k];
    const auto consider = [&](double s, const Vec2& on_poly) {
      const double dist2 = (a + s * d - on_poly).squaredNorm();
      if (dist2 < best2) best2 = dist2, best.s = s, best.on_section = on_poly;
    };
    consider(0, p + std::clamp((a - p).dot(e) * inv_el2, 0.0, 1.0) * e);
    consider(1, p + std::clamp((b - p).dot(e) * inv_el2, 0.0, 1.0) * e);
    consider(std::clamp((p - a).dot(d) * inv_dl2, 0.0, 1.0), p);
    // A segment lying parallel to an edge touches it along an interval: its middle.
    const double c = cross(d, e);
    if (inv_el2 > 0 && dl2 > 0 && c * c * inv_el2 <= 1e-18 * dl2) {
      const double el = std::sqrt(1 / inv_el2);
      const Vec2 t = e / el;
      const double sa = (a - p).dot(t), sb = (b - p).dot(t);
      const double lo = std::max(0.0, std::min(sa, sb)), hi = std::min(el, std::max(sa, sb));
      if (hi > lo) {
        const Vec2 mid = p + 0.5 * (lo + hi) * t;
        const double s = std::clamp((mid - a).dot(d) * inv_dl2, 0.0, 1.0);
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
  parts_[0].finish();
  back_ = -w;
  top_ = half;
  if (shape.sail_height > 0) {
    // The trailing strip, of the plate's thickness, turned up behind the width.
    const double h = shape.sail_height, rise = h / std::tan(std::max(shape.sail_angle, 1e-3));
    ConvexPolygon sail;
    sail.n = 5;
    sail.v = {Vec2(-w - t, -half), Vec2(-w, -half), Vec2(-w, half), Vec2(-w - rise, half + h), Vec2(-w - rise - t, half + h)};
    parts_[1] = sail;
    parts_[1].finish();
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
