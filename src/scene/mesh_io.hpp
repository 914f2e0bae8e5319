#pragma once
// User meshes (OBJ, OFF, PLY, STL) read into a labelled soup, with a clear error for
// an unreadable, empty or degenerate mesh.
#include <string>

#include "scene/soup.hpp"

namespace j232::scene {

// Every vertex of a scene lies within this distance of the spindle: a J232 set-up is a few
// metres across, and a mesh in the wrong units (mm read as m) is caught here.
inline constexpr double kMaxSceneRadius = 100.0;  // m
// Triangles in a whole scene, after target meshes are subdivided to carry the zone.
inline constexpr std::size_t kMaxSceneTriangles = 4'000'000;

// Reads `path`, scales coordinates by `scale` (file units to metres), triangulates
// polygons, and labels every face. Throws std::runtime_error naming the file and,
// for a bad face, its number.
Soup read_mesh(const std::string& path, Surface label, double scale, std::uint16_t guard = 0);

}  // namespace j232::scene
