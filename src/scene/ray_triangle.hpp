#pragma once
// The exact ray-triangle test every scene engine uses (docs/model.md §5.4): both engines
// (CGAL's AABB tree and Embree's BVH) only choose which triangles to test; this decides
// the hit, in double precision, with one rule for ties, so their answers are identical.
#include <array>
#include <cmath>
#include <cstdint>

#include "scene/scene.hpp"

namespace j232::scene {

// A ray with what box tests need precomputed.
struct RayQuery {
  Vec3 origin, dir, inverse;
  RayQuery(const Vec3& from, const Vec3& direction)
      : origin(from), dir(direction), inverse(1.0 / direction.x(), 1.0 / direction.y(), 1.0 / direction.z()) {}
};

// A triangle as its first corner and two edges from it.
using TriangleEdges = std::array<Vec3, 3>;

// The nearest accepted hit so far along a ray.
struct NearestHit {
  double distance;  // the search's reach at first, then the best hit's distance
  std::uint32_t face = Skip::kNone;

  // Tests triangle f (Moller-Trumbore, edges widened by 1e-12 so that a ray through a
  // shared edge meets both faces) and keeps it when it is nearer, or as near with a lower
  // face number (so the answer does not depend on the order triangles are visited). Hits
  // at ~0 are the surface being left, or a neighbour met at the same edge.
  void offer(const RayQuery& q, const TriangleEdges& t, std::uint32_t f, const Skip& skip) {
    if (skip.contains(f)) return;
    const Vec3 p = q.dir.cross(t[2]);
    const double det = t[1].dot(p);
    if (std::abs(det) < 1e-300) return;  // the ray runs within the triangle's plane
    const double inv = 1.0 / det;
    const Vec3 s = q.origin - t[0];
    const double u = s.dot(p) * inv;
    if (u < -1e-12 || u > 1 + 1e-12) return;
    const Vec3 qv = s.cross(t[1]);
    const double v = q.dir.dot(qv) * inv;
    if (v < -1e-12 || u + v > 1 + 1e-12) return;
    const double d = t[2].dot(qv) * inv;
    if (d > 1e-9 && (d < distance || (d == distance && f < face))) {
      distance = d;
      face = f;
    }
  }
};

}  // namespace j232::scene
