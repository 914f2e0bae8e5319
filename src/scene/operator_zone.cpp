#include "scene/operator_zone.hpp"

#include <cmath>

#include "units/arc.hpp"

namespace j232::scene {

OperatorZone::OperatorZone(const scenario::OperatorZoneSpec& spec, double blade_height) : spec_(spec), blade_centre_(0, 0, blade_height) {
  if (spec.kind == scenario::OperatorZoneSpec::Kind::Derived) {
    const double shoulder_z = spec.seat_z + spec.shoulder_height;
    spheres_.push_back({{spec.seat_x, spec.seat_y + spec.shoulder_half_width, shoulder_z}, spec.reach});
    spheres_.push_back({{spec.seat_x, spec.seat_y - spec.shoulder_half_width, shoulder_z}, spec.reach});
    // Knees ahead of the seat index point at seat height; the lower legs hang within knee height.
    spheres_.push_back({{spec.seat_x + 0.35, spec.seat_y, spec.seat_z}, spec.knee_height});
  }
}

bool OperatorZone::contains(const Vec3& p) const { return contains(p, blade_centre_); }

bool OperatorZone::contains(const Vec3& p, const Vec3& eye) const {
  if (spec_.kind == scenario::OperatorZoneSpec::Kind::Sector)
    return spec_.azimuth.contains(std::atan2(p.y(), p.x())) && p.z() >= spec_.bottom && p.z() <= spec_.top;
  // A nail crossing the board at p on a straight line from the blade: does that line,
  // continued beyond the board, enter the envelope?
  const Vec3 d = (p - eye).normalized();
  for (const auto& s : spheres_) {
    const Vec3 m = p - s.centre;
    const double b = m.dot(d);
    const double c = m.squaredNorm() - s.radius * s.radius;
    if (c <= 0.0) return true;                     // the board point is inside the envelope
    if (b < 0.0 && b * b - c >= 0.0) return true;  // the sphere lies ahead and the line meets it
  }
  return false;
}

}  // namespace j232::scene
