#include "scene/box_tree.hpp"

#include <algorithm>
#include <stdexcept>

namespace j232::scene {

BoxTree::BoxTree(const std::vector<Box>& faces) {
  if (faces.empty()) throw std::invalid_argument("a box tree needs at least one face");
  order_.resize(faces.size());
  for (std::uint32_t f = 0; f < faces.size(); ++f) order_[f] = f;
  nodes_.reserve(2 * faces.size() / kLeafSize + 2);
  build(faces, 0, static_cast<std::uint32_t>(faces.size()), 1);
}

// The node over order_[begin, end): split at the median of the faces' centres along the
// widest spread of those centres, down to kLeafSize faces (or the depth the query's stack holds).
std::uint32_t BoxTree::build(const std::vector<Box>& faces, std::uint32_t begin, std::uint32_t end, std::size_t depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  Box box{faces[order_[begin]].lo, faces[order_[begin]].hi};
  Vec3 clo = faces[order_[begin]].lo + faces[order_[begin]].hi, chi = clo;
  for (std::uint32_t i = begin; i < end; ++i) {
    const Box& b = faces[order_[i]];
    box.lo = box.lo.cwiseMin(b.lo), box.hi = box.hi.cwiseMax(b.hi);
    const Vec3 c = b.lo + b.hi;
    clo = clo.cwiseMin(c), chi = chi.cwiseMax(c);
  }
  nodes_.push_back({box, begin, end - begin});
  if (end - begin <= kLeafSize || depth + 1 >= kMaxDepth) return index;
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](std::uint32_t a, std::uint32_t b) {
    const double ca = faces[a].lo[axis] + faces[a].hi[axis], cb = faces[b].lo[axis] + faces[b].hi[axis];
    return ca < cb || (ca == cb && a < b);
  });
  nodes_[index].count = 0;
  build(faces, begin, mid, depth + 1);
  const std::uint32_t right = build(faces, mid, end, depth + 1);
  nodes_[index].first = right;
  return index;
}

}  // namespace j232::scene
