#include "flight/deck_outline.hpp"

#include <algorithm>

namespace j232::flight {

namespace {

// A monotone stand-in for the direction of (x, y) from the origin, in [0, 4) (0 along +x,
// 1 along +y, ...): one division instead of an atan2. Not defined at the origin.
double pseudo_angle(double x, double y) {
  if (y >= 0) return x >= 0 ? y / (x + y) : 1 - x / (y - x);
  return x < 0 ? 2 - y / (-x - y) : 3 + x / (x - y);
}

int sector_of(double pseudo, int sectors) { return std::min(sectors - 1, static_cast<int>(pseudo * sectors / 4)); }

// Whether pseudo-angle p lies in the cyclic interval [a, b).
bool in_cyclic(double p, double a, double b) { return a <= b ? (a <= p && p < b) : (p >= a || p < b); }

}  // namespace

DeckOutline::DeckOutline(std::vector<Eigen::Vector2d> vertices) : vertices_(std::move(vertices)) {
  if (empty()) return;
  // Beyond the farthest corner (with a margin for the test's tolerance): outside.
  double far = 0;
  for (const auto& v : vertices_) far = std::max(far, v.norm());
  outside_r2_ = (far + 1e-6) * (far + 1e-6);
  // Nearer the origin than every edge's line, the origin being inside: inside.
  double near = HUGE_VAL;
  const std::size_t n = vertices_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = vertices_[(i + n - 1) % n];
    const Eigen::Vector2d& b = vertices_[i];
    const double length = (b - a).norm();
    if (length > 0) near = std::min(near, ((b.x() - a.x()) * (-a.y()) - (b.y() - a.y()) * (-a.x())) / length);
  }
  if (!(near > 0) || !std::isfinite(near)) return;  // the origin is not strictly inside: no shortcuts
  inside_r2_ = near * near * (1 - 1e-9);

  // Each direction from the origin meets one edge (the polygon is convex about it): the
  // edge whose corners' directions bracket it. A sector's deciding edges run from the one
  // met at its start to the one met at its end, widened by a neighbour each side so that
  // a point near a corner sees both edges there.
  std::vector<double> corner(n);
  for (std::size_t i = 0; i < n; ++i) corner[i] = pseudo_angle(vertices_[i].x(), vertices_[i].y());
  const auto edge_met = [&](double p) -> std::size_t {
    for (std::size_t i = 0; i < n; ++i)
      if (in_cyclic(p, corner[(i + n - 1) % n], corner[i])) return i;
    return 0;  // not reached: the corners' directions go once round
  };
  sectors_.resize(kSectors);
  for (int s = 0; s < kSectors; ++s) {
    const std::size_t from = edge_met(4.0 * s / kSectors), to = edge_met(4.0 * (s + 1) / kSectors);
    const std::size_t span = (to + n - from) % n + 1 + 2;
    sectors_[static_cast<std::size_t>(s)] = {static_cast<std::uint32_t>((from + n - 1) % n), static_cast<std::uint32_t>(std::min(span, n))};
  }
}

bool DeckOutline::outside_edge(std::size_t i, double x, double y) const {
  const std::size_t n = vertices_.size();
  const Eigen::Vector2d& a = vertices_[(i + n - 1) % n];
  const Eigen::Vector2d& b = vertices_[i];
  return (b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x()) < -1e-9;
}

bool DeckOutline::contains_by_edges(std::uint32_t first, std::uint32_t count, double x, double y) const {
  const std::size_t n = vertices_.size();
  for (std::uint32_t k = 0; k < count; ++k)
    if (outside_edge((first + k) % n, x, y)) return false;
  return true;
}

bool DeckOutline::contains(double x, double y) const {
  const double r2 = x * x + y * y;
  if (r2 < inside_r2_) return true;
  if (r2 > outside_r2_) return false;
  if (sectors_.empty()) return contains_by_edges(0, static_cast<std::uint32_t>(vertices_.size()), x, y);
  const Sector& s = sectors_[static_cast<std::size_t>(sector_of(pseudo_angle(x, y), kSectors))];
  return contains_by_edges(s.first, s.count, x, y);
}

double DeckOutline::exit_fraction(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
  double t = 1;
  const std::size_t n = vertices_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = vertices_[(i + n - 1) % n];
    const Eigen::Vector2d& b = vertices_[i];
    const double ex = b.x() - a.x(), ey = b.y() - a.y();
    const double d_from = ex * (from.y() - a.y()) - ey * (from.x() - a.x());  // > 0: inside this edge
    const double d_to = ex * (to.y() - a.y()) - ey * (to.x() - a.x());
    if (d_to < 0 && d_from > d_to) t = std::min(t, std::max(0.0, d_from) / (d_from - d_to));
  }
  return t;
}

}  // namespace j232::flight
