#pragma once
// A bounding-box hierarchy over the scene's faces for the contact search's broad phase: which
// faces' boxes meet a query box. A box against a box needs no more than this (Embree's point
// query visits a sphere around the box, most of it empty, at several times the cost).

#include <array>
#include <cstdint>
#include <vector>

#include "invariant/check.hpp"
#include "scene/soup.hpp"

namespace j232::scene {

// An axis-aligned box.
struct Box {
  Vec3 lo, hi;
  // Whether the two boxes share a point (touching counts), exactly in double precision.
  bool meets(const Vec3& qlo, const Vec3& qhi) const {
    // (Written out: Eigen's array comparisons with any() cost the broad phase a third of its time.)
    return !(lo.x() > qhi.x() || lo.y() > qhi.y() || lo.z() > qhi.z() || hi.x() < qlo.x() || hi.y() < qlo.y() || hi.z() < qlo.z());
  }
};

class BoxTree {
 public:
  explicit BoxTree(const std::vector<Box>& faces);

  // Calls visit(f) for every face f whose box meets [lo, hi], each once, in no set order.
  // Allocation-free.
  template <class Visit>
  void visit(const std::vector<Box>& faces, const Vec3& lo, const Vec3& hi, Visit&& visit) const {
    std::array<std::uint32_t, kMaxDepth> stack;  // NOLINT: filled as it is used
    std::size_t top = 0;
    std::uint32_t node = 0;
    for (;;) {
      const Node& n = nodes_[node];
      if (n.box.meets(lo, hi)) {
        if (n.count > 0) {
          for (std::uint32_t i = n.first; i < n.first + n.count; ++i)
            if (faces[order_[i]].meets(lo, hi)) visit(order_[i]);
        } else {
          J232_CHECK(top < kMaxDepth);  // the build stops at that depth
          stack[top++] = n.first;  // the right child, after the left one (the next node)
          node = node + 1;
          continue;
        }
      }
      if (top == 0) return;
      node = stack[--top];
    }
  }

 private:
  static constexpr std::size_t kMaxDepth = 64;
  static constexpr std::uint32_t kLeafSize = 4;
  struct Node {
    Box box;              // holds the boxes of every face below
    std::uint32_t first;  // a leaf: its first face in order_; else: the right child's index
    std::uint32_t count;  // a leaf: how many faces (> 0); else 0 (the left child is the next node)
  };
  std::uint32_t build(const std::vector<Box>& faces, std::uint32_t begin, std::uint32_t end, std::size_t depth);
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;
};

}  // namespace j232::scene
