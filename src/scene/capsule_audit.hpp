#pragma once
// An audit of a capsule's poses against a scene's faces, independent of the contact search
// it checks (flight/face_touch.hpp): every face of the soup, brute force, with CGAL's own
// distance and intersection tests (docs/validation.md: `j232 trace --check`). Kept apart
// from the search so that an error in one is not repeated in the other.
#include <cstdint>
#include <utility>
#include <vector>

#include "scene/soup.hpp"

namespace j232::scene {

struct Overlap {
  double depth = 0;  // m the capsule reaches into the face (<= 0: clear of every face)
  std::uint32_t face = 0;
  Surface label = Surface::Ground;
};

// The deepest overlap of the capsule (core from centre - h axis to centre + h axis, radius r)
// with any face of the soup; faces of `skip_guard` (a guard's curtain the nail is passing
// through; -1: none) are left out.
// `allowed`: faces the capsule may lie in by a given depth (a field's object starts pressed
// into the soil, or under a chain curtain draped over it): only what lies deeper counts.
// (kAnyGround stands for every ground face: the soil is one medium however it is tiled.)
using Allowances = std::vector<std::pair<std::uint32_t, double>>;
inline constexpr std::uint32_t kAnyGround = 0xFFFFFFFFu;
Overlap deepest_overlap(const Soup& soup, const Vec3& centre, const Vec3& axis, double h, double r, int skip_guard = -1,
                        const Allowances* allowed = nullptr);
// Every face the capsule reaches into, with its depth.
Allowances overlaps(const Soup& soup, const Vec3& centre, const Vec3& axis, double h, double r);

}  // namespace j232::scene
