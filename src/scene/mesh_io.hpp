#pragma once
// User meshes (OBJ, OFF, PLY, STL) read into a labelled soup, with a clear error for
// an unreadable, empty or degenerate mesh.
#include <string>

#include "scene/soup.hpp"

namespace j232::scene {

// Reads `path`, scales coordinates by `scale` (file units to metres), triangulates
// polygons, and labels every face. Throws std::runtime_error naming the file and,
// for a bad face, its number.
Soup read_mesh(const std::string& path, Surface label, double scale, std::uint16_t guard = 0);

}  // namespace j232::scene
