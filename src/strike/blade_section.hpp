#pragma once
// The blade near its edge, in section (docs/model.md §5.1a). Seen along the arm, the
// blade is a plate: its leading edge at u = 0, its width behind it (u < 0, u along the
// blade's motion), its thickness about its mid-plane (w = 0, w up). The edge is bevelled
// on one side: the bevel face runs from the sharp edge, on the other face, back at the
// bevel angle to the bevelled face; 90 deg is a square edge. An optional sail (the
// trailing strip turned up, as on lift blades) rises behind the width at the sail angle.
// Both parts are convex polygons; the plate is taken as straight along the arm (the
// section is the same at every radius out to the tip).
#include <Eigen/Dense>
#include <array>

namespace j232::strike {

using Vec2 = Eigen::Vector2d;

struct EdgeShape {
  double thickness = 0.006;    // m
  double width = 0.10;         // m, the plate behind the edge
  double bevel_angle = 30 * 3.141592653589793 / 180;  // rad, between the bevel face and the blade plane (pi/2: square)
  bool bevel_on_top = true;    // the sharp edge on the bottom face, the bevel face up
  double sail_height = 0.0;    // m above the top face (0: no sail)
  double sail_angle = 45 * 3.141592653589793 / 180;  // rad, of the sail against the blade plane
};

struct ConvexPolygon {
  std::array<Vec2, 6> v{};  // counter-clockwise in (u, w)
  int n = 0;
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();  // bounding box
  std::array<Vec2, 6> edge{};          // v[i+1] - v[i]
  std::array<double, 6> inv_len2{};    // 1 / |edge|^2 (0 for a degenerate edge)
  // The box and edges from the vertices.
  void finish();
};

// The nearest approach of a segment to the section.
struct SectionApproach {
  double distance = 0;  // segment to section, m; 0 when they overlap
  double s = 0;         // where on the segment, 0 (a) to 1 (b)
  Vec2 on_section = Vec2::Zero();
  Vec2 normal = Vec2::UnitX();  // unit, from the section toward the segment (valid when distance > 0)
};

class BladeSection {
 public:
  BladeSection() = default;
  explicit BladeSection(const EdgeShape& shape);
  const EdgeShape& shape() const { return shape_; }
  // The section's extent: everything lies in u in [back(), 0] and w in [bottom(), top()].
  double back() const { return back_; }
  double bottom() const { return -0.5 * shape_.thickness; }
  double top() const { return top_; }
  int parts() const { return count_; }
  const ConvexPolygon& part(int k) const { return parts_[static_cast<std::size_t>(k)]; }

  // The segment a-b (a capsule's core, in section coordinates) against the section.
  SectionApproach approach(const Vec2& a, const Vec2& b) const;

 private:
  EdgeShape shape_;
  std::array<ConvexPolygon, 2> parts_{};
  int count_ = 0;
  double back_ = 0, top_ = 0;
};

// Point-to-segment and segment-to-polygon distances in the plane (exposed for tests).
SectionApproach segment_to_polygon(const Vec2& a, const Vec2& b, const ConvexPolygon& p);

}  // namespace j232::strike
