#pragma once
// A labelled triangle soup: the scene's geometry before it is indexed. Generators and
// mesh readers produce it; Scene indexes it (CGAL) for ray queries.
#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace j232::scene {

using Vec3 = Eigen::Vector3d;

// What a surface is, which decides what a nail does there (docs/model.md §5.3).
enum class Surface : std::uint8_t { Ground, Housing, Deflector, Guard, TargetOutside, TargetZone };
inline constexpr int kSurfaceKinds = 6;

std::string_view name(Surface s);  // "ground", "housing", ..., "target", "operator_zone"
inline bool is_target(Surface s) { return s == Surface::TargetOutside || s == Surface::TargetZone; }

// A line for a viewer, not a surface: exported with the scene (scene/markers.hpp).
struct Polyline {
  std::string group;                   // "tip_circles", "feed_stations", "seat", "reach_envelope", "nail_paths"
  std::array<std::uint8_t, 3> colour;  // for a viewer
  std::vector<Vec3> points;
  bool closed = false;  // the last point joins the first
};

struct Soup {
  std::vector<Vec3> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<Surface> labels;             // per triangle
  std::vector<std::uint16_t> guard_index;  // per triangle: which guard's properties (guards only)

  std::uint32_t add_point(const Vec3& p) {
    points.push_back(p);
    return static_cast<std::uint32_t>(points.size() - 1);
  }
  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, Surface label, std::uint16_t guard = 0) {
    triangles.push_back({a, b, c});
    labels.push_back(label);
    guard_index.push_back(guard);
  }
  void add_quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d, Surface label, std::uint16_t guard = 0) {
    add_triangle(a, b, c, label, guard);
    add_triangle(a, c, d, label, guard);
  }
  void append(const Soup& other);
};

}  // namespace j232::scene
