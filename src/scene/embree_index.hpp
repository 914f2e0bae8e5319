#pragma once
// Embree's BVH over the scene's triangles, as user primitives: Embree traverses (fast,
// SIMD, single precision with boxes widened to stay conservative) and every candidate
// triangle is decided by the exact double-precision test of ray_triangle.hpp, so the
// hits are those of the CGAL engine, bit for bit (docs/model.md §5.4). Only built when
// Embree 3 is found at configure time (J232_HAVE_EMBREE).
#include <memory>
#include <vector>

#include "scene/ray_triangle.hpp"

namespace j232::scene {

class EmbreeIndex {
 public:
  explicit EmbreeIndex(const std::vector<TriangleEdges>& triangles);  // kept by reference: must outlive this
  ~EmbreeIndex();
  EmbreeIndex(const EmbreeIndex&) = delete;
  EmbreeIndex& operator=(const EmbreeIndex&) = delete;

  // The nearest hit within best.distance (which it lowers), skipping `skip`.
  void closest(const RayQuery& q, const Skip& skip, NearestHit& best) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace j232::scene
