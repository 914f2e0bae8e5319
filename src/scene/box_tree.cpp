#include "scene/box_tree.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace j232::scene {

BoxTree::BoxTree(const std::vector<Box>& faces) {
  if (faces.empty()) throw std::invalid_argument("a box tree needs at least one face");
  order_.resize(faces.size());
  for (std::uint32_t f = 0; f < faces.size(); ++f) order_[f] = f;
  nodes_.reserve(2 * faces.size() / kLeafSize + 2);
  build(faces, 0, static_cast<std::uint32_t>(faces.size()), 1);
}

namespace {
// Half the surface area of a box: a query box's chance of meeting it grows with it (the
// surface area heuristic), so a split is judged by each side's area times its faces.
double half_area(const Box& b) {
  const Vec3 d = (b.hi - b.lo).cwiseMax(0.0);
  return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
}
Box empty_box() { return {Vec3::Constant(HUGE_VAL), Vec3::Constant(-HUGE_VAL)}; }
void grow(Box& into, const Box& b) { into.lo = into.lo.cwiseMin(b.lo), into.hi = into.hi.cwiseMax(b.hi); }
}  // namespace

// The node over order_[begin, end): split where the surface area heuristic finds the
// cheapest pair of sides, among kBins planes across the spread of the faces' centres along
// each axis (a ring of board faces round the deck would otherwise give nodes whose boxes span
// the deck, visited by every query inside it); at the median of the widest spread when no
// plane separates them; down to kLeafSize faces (or the depth the query's stack holds).
std::uint32_t BoxTree::build(const std::vector<Box>& faces, std::uint32_t begin, std::uint32_t end, std::size_t depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  Box box = empty_box(), centres = empty_box();
  for (std::uint32_t i = begin; i < end; ++i) {
    const Box& b = faces[order_[i]];
    grow(box, b);
    const Vec3 c = b.lo + b.hi;
    grow(centres, {c, c});
  }
  nodes_.push_back({box, begin, end - begin});
  if (end - begin <= kLeafSize || depth + 1 >= kMaxDepth) return index;
  constexpr int kBins = 16;
  const auto bin_of = [&](std::uint32_t f, int axis) {
    const double c = faces[f].lo[axis] + faces[f].hi[axis], lo = centres.lo[axis], spread = centres.hi[axis] - lo;
    return std::min(kBins - 1, static_cast<int>(kBins * (c - lo) / spread));
  };
  int best_axis = -1, best_bin = 0;
  double best_cost = HUGE_VAL;
  for (int axis = 0; axis < 3; ++axis) {
    if (!(centres.hi[axis] > centres.lo[axis])) continue;
    std::array<Box, kBins> bins;
    bins.fill(empty_box());
    std::array<std::uint32_t, kBins> counts{};
    for (std::uint32_t i = begin; i < end; ++i) {
      const int k = bin_of(order_[i], axis);
      grow(bins[static_cast<std::size_t>(k)], faces[order_[i]]), ++counts[static_cast<std::size_t>(k)];
    }
    // The cost of each split after bin k: the sides' areas times their counts.
    std::array<double, kBins> right_cost{};
    Box right = empty_box();
    std::uint32_t right_count = 0;
    for (int k = kBins - 1; k > 0; --k) {
      grow(right, bins[static_cast<std::size_t>(k)]), right_count += counts[static_cast<std::size_t>(k)];
      right_cost[static_cast<std::size_t>(k - 1)] = right_count > 0 ? half_area(right) * right_count : 0.0;
    }
    Box left = empty_box();
    std::uint32_t left_count = 0;
    for (int k = 0; k + 1 < kBins; ++k) {
      grow(left, bins[static_cast<std::size_t>(k)]), left_count += counts[static_cast<std::size_t>(k)];
      if (left_count == 0 || left_count == end - begin) continue;
      const double cost = half_area(left) * left_count + right_cost[static_cast<std::size_t>(k)];
      if (cost < best_cost) best_cost = cost, best_axis = axis, best_bin = k;
    }
  }
  std::uint32_t mid = begin + (end - begin) / 2;
  if (best_axis >= 0) {
    mid = static_cast<std::uint32_t>(std::partition(order_.begin() + begin, order_.begin() + end,
                                                    [&](std::uint32_t f) { return bin_of(f, best_axis) <= best_bin; }) -
                                     order_.begin());
  } else {  // every centre in one point: halves of the list
    int axis = 0;
    (centres.hi - centres.lo).maxCoeff(&axis);
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](std::uint32_t a, std::uint32_t b) {
      const double ca = faces[a].lo[axis] + faces[a].hi[axis], cb = faces[b].lo[axis] + faces[b].hi[axis];
      return ca < cb || (ca == cb && a < b);
    });
  }
  J232_CHECK(mid > begin && mid < end);
  nodes_[index].count = 0;
  build(faces, begin, mid, depth + 1);
  const std::uint32_t right = build(faces, mid, end, depth + 1);
  nodes_[index].first = right;
  return index;
}

}  // namespace j232::scene
