// CGAL's polygon-soup readers (the second and last translation unit that includes CGAL).
#include "scene/mesh_io.hpp"

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <fmt/format.h>
#include <stdexcept>

namespace j232::scene {

namespace {
constexpr std::uintmax_t kMaxMeshBytes = 512ull << 20;
constexpr std::size_t kMaxMeshFaces = 2'000'000;

// CGAL 5.5's PLY reader trusts its header (a `property` before any `element`, or a vertex
// coordinate of a type it has no reader for or given as a list, crashes it; a 32-bit list count lets one face
// allocate gigabytes; all found by fuzzing): the header is checked here first. Empty when
// sound.
std::string ply_header_problem(const std::string& path) {
  static const std::set<std::string> kTypes = {"char", "uchar", "short", "ushort", "int",   "uint",   "float",   "double",
                                               "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
  static const std::set<std::string> kReal = {"float", "double", "float32", "float64"};
  std::ifstream in(path, std::ios::binary);
  std::string line;
  if (!std::getline(in, line) || line.rfind("ply", 0) != 0) return "does not start with \"ply\"";
  std::error_code ec;
  const auto bytes = static_cast<long long>(std::filesystem::file_size(path, ec));
  bool element = false;
  std::string element_name;
  long long element_count = 0, properties = 0;
  // An element read from nothing would keep CGAL's reader looping for as many items as its
  // count (found by fuzzing): every item takes at least a byte of the file.
  auto element_problem = [&](int n) -> std::string {
    if (element && element_count > 0 && properties == 0) return fmt::format("line {}: element with items but no properties", n);
    return {};
  };
  for (int n = 2; n < 10000 && std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "end_header") return element_problem(n);
    if (word == "element") {
      if (auto problem = element_problem(n); !problem.empty()) return problem;
      std::string name;
      long long count = -1;
      if (!(words >> name >> count) || count < 0) return fmt::format("line {}: expected \"element NAME COUNT\"", n);
      if (count > bytes) return fmt::format("line {}: {} items, more than the file has bytes", n, count);
      element = true;
      element_name = name;
      element_count = count;
      properties = 0;
    } else if (word == "property") {
      ++properties;
      if (!element) return fmt::format("line {}: a property before any element", n);
      std::string type, name;
      words >> type;
      const bool list = type == "list";
      if (list) {
        std::string count_type;
        words >> count_type >> type;
        if (!kTypes.count(count_type)) return fmt::format("line {}: unknown property type", n);
        // A list's length is allocated as read: with a 32-bit count one face can ask for
        // gigabytes (found by fuzzing). Exporters write uchar counts.
        if (count_type != "uchar" && count_type != "uint8" && count_type != "ushort" && count_type != "uint16")
          return fmt::format("line {}: a list's count must be uchar or ushort", n);
      }
      if (!(words >> name) || !kTypes.count(type)) return fmt::format("line {}: expected \"property TYPE NAME\"", n);
      // CGAL reads a vertex's coordinates as numbers and a face's indices as a list, casting
      // without a check: a list coordinate (or scalar indices) is a null dereference in it
      // (found by fuzzing).
      if (element_name == "vertex" && (name == "x" || name == "y" || name == "z") && (list || !kReal.count(type)))
        return fmt::format("line {}: vertex coordinate {} must be a float or double, not a list", n, name);
      if (element_name == "face" && (name == "vertex_indices" || name == "vertex_index") && !list)
        return fmt::format("line {}: a face's {} must be a list", n, name);
    } else if (word != "format" && word != "comment" && word != "obj_info" && !word.empty()) {
      return fmt::format("line {}: unknown header keyword \"{}\"", n, word.substr(0, 40));
    }
  }
  return "no end_header";
}

// Plain OFF is read here rather than by CGAL 5.5, whose scanner converts a face's vertex
// index to an integer without checking it (a huge or fractional index is undefined
// behaviour) and reads comments by rules of its own, so that a check made beforehand
// could pass a file CGAL then reads differently (all found by fuzzing). Every token is
// checked as it is read.
struct PlainOff {
  std::string problem;  // empty when sound
  std::vector<CGAL::Simple_cartesian<double>::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
};

PlainOff read_plain_off(const std::string& path) {
  PlainOff off;
  std::ifstream in(path, std::ios::binary);
  std::vector<std::vector<std::string>> lines;  // non-empty, comments stripped
  std::string line;
  while (std::getline(in, line) && lines.size() < 30'000'000) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::vector<std::string> w;
    for (std::string t; words >> t;) w.push_back(t);
    if (!w.empty()) lines.push_back(std::move(w));
  }
  const auto whole = [](const std::string& t, unsigned long long& v) {
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    return ec == std::errc() && p == t.data() + t.size();
  };
  const auto real = [](const std::string& t, double& v) {
    auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    return ec == std::errc() && p == t.data() + t.size();
  };
  const auto refuse = [&off](std::string why) {
    off.problem = std::move(why);
    off.points.clear();
    off.polygons.clear();
    return std::move(off);
  };
  if (lines.empty() || lines[0][0] != "OFF") return refuse("expected a plain OFF file (first word OFF)");
  std::size_t k = 0;
  std::vector<std::string> counts(lines[0].begin() + 1, lines[0].end());
  if (counts.empty()) {
    if (lines.size() < 2) return refuse("no vertex, face and edge counts");
    counts = lines[++k];
  }
  ++k;
  unsigned long long nv = 0, nf = 0, ne = 0;
  if (counts.size() != 3 || !whole(counts[0], nv) || !whole(counts[1], nf) || !whole(counts[2], ne))
    return refuse("expected the vertex, face and edge counts as three whole numbers on one line");
  if (nv > 10'000'000 || nf > kMaxMeshFaces || ne > 100'000'000) return refuse("too many vertices, faces or edges");
  if (lines.size() < k + nv + nf) return refuse("fewer vertex or face lines than the header says");
  off.points.reserve(nv);
  for (unsigned long long v = 0; v < nv; ++v) {
    const auto& w = lines[k + v];
    double x = 0, y = 0, z = 0;
    if (w.size() < 3 || !real(w[0], x) || !real(w[1], y) || !real(w[2], z))
      return refuse(fmt::format("vertex {}: expected three coordinates", v + 1));
    off.points.emplace_back(x, y, z);
  }
  k += nv;
  off.polygons.reserve(nf);
  for (unsigned long long f = 0; f < nf; ++f) {
    const auto& w = lines[k + f];
    unsigned long long n = 0, index = 0;
    if (!whole(w[0], n) || n < 3 || n > 1000 || w.size() < n + 1) return refuse(fmt::format("face {}: bad corner count", f + 1));
    auto& polygon = off.polygons.emplace_back();
    for (unsigned long long c = 1; c <= n; ++c) {  // a colour may follow the corners
      if (!whole(w[c], index) || index >= nv)
        return refuse(fmt::format("face {}: a corner is not a vertex index from 0 to {}", f + 1, nv == 0 ? 0 : nv - 1));
      polygon.push_back(static_cast<std::size_t>(index));
    }
  }
  return off;
}
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
    throw std::runtime_error(
        fmt::format("{}: larger than {} MB; simplify the mesh (a mower deck needs thousands of "
                    "triangles, not millions)",
                    path, kMaxMeshBytes >> 20));
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".stl")
    throw std::runtime_error(fmt::format("{}: unknown mesh format \"{}\" (expected .obj, .off, .ply or .stl)", path, ext));
  if (ext == ".ply")
    if (const std::string problem = ply_header_problem(path); !problem.empty())
      throw std::runtime_error(fmt::format("{}: malformed PLY header: {}", path, problem));
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  if (ext == ".off") {
    PlainOff off = read_plain_off(path);
    if (!off.problem.empty()) throw std::runtime_error(fmt::format("{}: malformed OFF file: {}", path, off.problem));
    points = std::move(off.points);
    polygons = std::move(off.polygons);
    ok = true;
  } else {
    try {
      if (ext == ".obj") {
        // Line elements ("l", polylines such as `j232 scene --export` writes) are valid OBJ,
        // but CGAL 5.5's reader refuses the file for them: they carry no faces, so skip them.
        std::ifstream in(path);
        std::string text, line;
        while (std::getline(in, line)) {
          if (line.size() > 1 && line[0] == 'l' && (line[1] == ' ' || line[1] == '\t')) line = "#";
          text += line, text += '\n';
        }
        std::istringstream soup_text(text);
        ok = CGAL::IO::read_OBJ(soup_text, points, polygons, CGAL::parameters::verbose(false));
      } else {
        ok = CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false));
      }
    } catch (const std::exception& e) {
      throw std::runtime_error(fmt::format("{}: cannot read the mesh: {}", path, e.what()));
    }
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
      throw std::runtime_error(
          fmt::format("{}: vertex {} lies {:.3g} m from the spindle after scaling by {:g}; expected a "
                      "mower-sized scene within {:g} m (is `scale` right for the file's units?)",
                      path, soup.points.size() + 1, v.norm(), scale, kMaxSceneRadius));
    soup.add_point(v);
  }
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& poly = polygons[f];
    if (poly.size() < 3) throw std::runtime_error(fmt::format("{}: face {} has {} corners (need 3 or more)", path, f + 1, poly.size()));
    for (std::size_t i : poly)
      if (i >= points.size())
        throw std::runtime_error(
            fmt::format("{}: face {} names a vertex that does not exist (the file has vertices 1 to {})", path, f + 1, points.size()));
    // Fan triangulation; every triangle must have area.
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
      const Vec3& a = soup.points[poly[0]];
      const Vec3& b = soup.points[poly[k]];
      const Vec3& c = soup.points[poly[k + 1]];
      const double size2 = (b - a).squaredNorm() + (c - a).squaredNorm();
      if (!((b - a).cross(c - a).norm() > 1e-12 * size2) || size2 == 0.0)
        throw std::runtime_error(fmt::format("{}: face {} is degenerate (zero area)", path, f + 1));
      soup.add_triangle(static_cast<std::uint32_t>(poly[0]), static_cast<std::uint32_t>(poly[k]), static_cast<std::uint32_t>(poly[k + 1]),
                        label, guard);
    }
  }
  return soup;
}

}  // namespace j232::scene
