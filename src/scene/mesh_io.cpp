// CGAL's polygon-soup readers (the second and last translation unit that includes CGAL).
#include "scene/mesh_io.hpp"

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>
#include <filesystem>
#include <fmt/format.h>
#include <stdexcept>

namespace j232::scene {

namespace {
constexpr std::uintmax_t kMaxMeshBytes = 512ull << 20;
constexpr std::size_t kMaxMeshFaces = 2'000'000;
}  // namespace

Soup read_mesh(const std::string& path, Surface label, double scale, std::uint16_t guard) {
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);  // follows links: what would be read
  if (ec || !std::filesystem::exists(status)) throw std::runtime_error(fmt::format("{}: no such mesh file", path));
  // A device, pipe or folder could block for ever or never end: only plain files are meshes.
  if (!std::filesystem::is_regular_file(status))
    throw std::runtime_error(fmt::format("{}: not a regular file (a mesh must be an OBJ, OFF, PLY or STL file)", path));
  if (std::filesystem::file_size(path, ec) > kMaxMeshBytes)
    throw std::runtime_error(fmt::format("{}: larger than {} MB; simplify the mesh (a mower deck needs thousands of "
                                         "triangles, not millions)", path, kMaxMeshBytes >> 20));
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".stl")
    throw std::runtime_error(fmt::format("{}: unknown mesh format \"{}\" (expected .obj, .off, .ply or .stl)", path, ext));
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false));
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{}: cannot read the mesh: {}", path, e.what()));
  }
  if (!ok) throw std::runtime_error(fmt::format("{}: cannot read the mesh (malformed {} file)", path, ext));
  if (polygons.empty()) throw std::runtime_error(fmt::format("{}: the mesh has no faces", path));
  if (polygons.size() > kMaxMeshFaces)
    throw std::runtime_error(fmt::format("{}: {} faces; expected at most {}", path, polygons.size(), kMaxMeshFaces));

  Soup soup;
  for (const Point& p : points) {
    const Vec3 v(p.x() * scale, p.y() * scale, p.z() * scale);
    if (!v.allFinite()) throw std::runtime_error(fmt::format("{}: a vertex has a non-finite coordinate", path));
    if (v.norm() > kMaxSceneRadius)
      throw std::runtime_error(fmt::format("{}: vertex {} lies {:.3g} m from the spindle after scaling by {:g}; expected a "
                                           "mower-sized scene within {:g} m (is `scale` right for the file's units?)",
                                           path, soup.points.size() + 1, v.norm(), scale, kMaxSceneRadius));
    soup.add_point(v);
  }
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& poly = polygons[f];
    if (poly.size() < 3) throw std::runtime_error(fmt::format("{}: face {} has {} corners (need 3 or more)", path, f + 1, poly.size()));
    for (std::size_t i : poly)
      if (i >= points.size())
        throw std::runtime_error(fmt::format("{}: face {} names a vertex that does not exist (the file has vertices 1 to {})",
                                             path, f + 1, points.size()));
    // Fan triangulation; every triangle must have area.
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
      const Vec3& a = soup.points[poly[0]];
      const Vec3& b = soup.points[poly[k]];
      const Vec3& c = soup.points[poly[k + 1]];
      const double size2 = (b - a).squaredNorm() + (c - a).squaredNorm();
      if (!((b - a).cross(c - a).norm() > 1e-12 * size2) || size2 == 0.0)
        throw std::runtime_error(fmt::format("{}: face {} is degenerate (zero area)", path, f + 1));
      soup.add_triangle(static_cast<std::uint32_t>(poly[0]), static_cast<std::uint32_t>(poly[k]),
                        static_cast<std::uint32_t>(poly[k + 1]), label, guard);
    }
  }
  return soup;
}

}  // namespace j232::scene
