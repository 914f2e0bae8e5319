// CGAL's distance tests only (no AABB tree): a light translation unit.
#include "scene/capsule_audit.hpp"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/squared_distance_3.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>

namespace j232::scene {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
Point point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
}  // namespace

namespace {
// Visits every face within the capsule's reach with its depth (r - distance).
template <class Visit>
void each_depth(const Soup& soup, const Vec3& centre, const Vec3& axis, double h, double r, Visit visit) {
  const Vec3 p0 = centre - h * axis, p1 = centre + h * axis;
  const Vec3 lo = p0.cwiseMin(p1).array() - r, hi = p0.cwiseMax(p1).array() + r;
  const Kernel::Segment_3 core(point(p0), point(p1));
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    const auto& t = soup.triangles[f];
    const Vec3 &a = soup.points[t[0]], &b = soup.points[t[1]], &c = soup.points[t[2]];
    const Vec3 tlo = a.cwiseMin(b).cwiseMin(c), thi = a.cwiseMax(b).cwiseMax(c);
    if ((tlo.array() > hi.array()).any() || (thi.array() < lo.array()).any()) continue;  // cannot reach it
    const Kernel::Triangle_3 tri(point(a), point(b), point(c));
    double d2;
    if (h > 0 && CGAL::do_intersect(core, tri)) {
      d2 = 0;
    } else {
      d2 = CGAL::squared_distance(point(p0), tri);
      if (h > 0) {
        d2 = std::min(d2, CGAL::squared_distance(point(p1), tri));
        for (int e = 0; e < 3; ++e)
          d2 = std::min(d2, CGAL::squared_distance(core, Kernel::Segment_3(tri.vertex(e), tri.vertex(e + 1))));
      }
    }
    visit(f, r - std::sqrt(d2));
  }
}
}  // namespace

Overlap deepest_overlap(const Soup& soup, const Vec3& centre, const Vec3& axis, double h, double r, int skip_guard,
                        const Allowances* allowed) {
  Overlap worst{-HUGE_VAL, 0, Surface::Ground};
  each_depth(soup, centre, axis, h, r, [&](std::uint32_t f, double depth) {
    if (skip_guard >= 0 && soup.labels[f] == Surface::Guard && soup.guard_index[f] == static_cast<std::uint16_t>(skip_guard)) return;
    if (allowed)
      for (const auto& [face, allowance] : *allowed)
        if (face == f || (face == kAnyGround && soup.labels[f] == Surface::Ground)) depth -= allowance;
    if (depth > worst.depth) worst = {depth, f, soup.labels[f]};
  });
  return worst;
}

Allowances overlaps(const Soup& soup, const Vec3& centre, const Vec3& axis, double h, double r) {
  Allowances out;
  each_depth(soup, centre, axis, h, r, [&](std::uint32_t f, double depth) {
    if (depth > 0) out.emplace_back(f, depth);
  });
  return out;
}

}  // namespace j232::scene
