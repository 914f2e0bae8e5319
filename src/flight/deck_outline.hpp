#pragma once
// The deck's outline in plan (convex, counter-clockwise), asked after every chord of every
// nail whether the nail is still inside it, and once per nail where a move left it
// (docs/model.md §5.3a). Most points are settled by two circles about the origin (surely
// inside the inscribed one, surely outside the circumscribed one); the rest, which lie
// near the skirt where nails bounce, by the edge that faces them: a table indexed by
// direction from the origin names the one or two edges that can decide, instead of a pass
// over all of them (a round deck has 96).
#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <vector>

namespace j232::flight {

class DeckOutline {
 public:
  DeckOutline() = default;
  // `vertices`: convex, counter-clockwise; fewer than three: no outline (empty()).
  explicit DeckOutline(std::vector<Eigen::Vector2d> vertices);

  bool empty() const { return vertices_.size() < 3; }
  const std::vector<Eigen::Vector2d>& vertices() const { return vertices_; }

  // Whether (x, y) lies inside (on the outline counts as inside, within 1e-9 m^2 of an
  // edge's cross product).
  bool contains(double x, double y) const;

  // Where the straight move from `from` (inside) to `to` (outside) leaves the outline, as a
  // fraction of the move: the first crossing of an edge's line outward (Cyrus-Beck clipping).
  double exit_fraction(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

 private:
  static constexpr int kSectors = 256;  // directions from the origin, by pseudo-angle
  struct Sector {
    std::uint32_t first = 0, count = 0;  // edges first .. first + count - 1 (cyclic), edge i ends at vertex i
  };
  bool outside_edge(std::size_t i, double x, double y) const;
  bool contains_by_edges(std::uint32_t first, std::uint32_t count, double x, double y) const;

  std::vector<Eigen::Vector2d> vertices_;
  double inside_r2_ = 0, outside_r2_ = HUGE_VAL;
  std::vector<Sector> sectors_;  // empty when the origin is not inside: every test is then a full pass
};

}  // namespace j232::flight
