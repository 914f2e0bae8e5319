#pragma once
// Which part of the target board is the operator zone (docs/model.md §5.4): an explicit
// sector (azimuth and height ranges), or derived from a seated operator: the board
// points through which a straight line from the blade reaches the 95th-percentile
// reach envelope — spheres of the extended reach about each shoulder, and a sphere
// of knee-height radius about the knees.
#include <vector>

#include "scenario/scenario.hpp"
#include "scene/soup.hpp"

namespace j232::scene {

class OperatorZone {
 public:
  OperatorZone(const scenario::OperatorZoneSpec& spec, double blade_height);
  bool contains(const Vec3& board_point) const;  // seen from the blade's centre at the origin
  // Seen from `eye` (a spindle's blade centre): the line from it through the board point.
  bool contains(const Vec3& board_point, const Vec3& eye) const;

  struct Sphere {
    Vec3 centre;
    double radius;
  };
  const std::vector<Sphere>& envelope() const { return spheres_; }

 private:
  scenario::OperatorZoneSpec spec_;
  Vec3 blade_centre_;
  std::vector<Sphere> spheres_;
};

}  // namespace j232::scene
