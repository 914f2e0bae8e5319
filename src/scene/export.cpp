#include <fmt/format.h>

#include <filesystem>
#include <iterator>
#include <stdexcept>

#include "scene/scene.hpp"

namespace j232::scene {

namespace {

std::size_t segment_count(const Polyline& p) {
  if (p.points.size() < 2) return 0;
  return p.points.size() - 1 + (p.closed && p.points.size() > 2 ? 1 : 0);
}

std::string ply(const Soup& soup, const std::vector<Polyline>& lines) {
  std::size_t points = soup.points.size(), edges = 0;
  for (const auto& l : lines) points += l.points.size(), edges += segment_count(l);
  std::string o;
  auto out = std::back_inserter(o);
  fmt::format_to(out,
                 "ply\nformat ascii 1.0\ncomment j232 labelled scene: label 0 ground, 1 housing, 2 deflector, 3 guard, "
                 "4 target, 5 operator_zone\n");
  if (edges) fmt::format_to(out, "comment edges: tip circles, feed stations, seat, reach envelope and nail paths, coloured by kind\n");
  fmt::format_to(out,
                 "element vertex {}\nproperty double x\nproperty double y\nproperty double z\n"
                 "element face {}\nproperty list uchar int vertex_indices\nproperty uchar label\n"
                 "property uchar red\nproperty uchar green\nproperty uchar blue\n",
                 points, soup.triangles.size());
  if (edges)
    fmt::format_to(out,
                   "element edge {}\nproperty int vertex1\nproperty int vertex2\nproperty uchar red\nproperty uchar green\n"
                   "property uchar blue\n",
                   edges);
  fmt::format_to(out, "end_header\n");
  for (const auto& p : soup.points) fmt::format_to(out, "{} {} {}\n", p.x(), p.y(), p.z());
  for (const auto& l : lines)
    for (const auto& p : l.points) fmt::format_to(out, "{} {} {}\n", p.x(), p.y(), p.z());
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    const int l = static_cast<int>(soup.labels[t]);
    const auto c = label_rgb(soup.labels[t]);
    fmt::format_to(out, "3 {} {} {} {} {} {} {}\n", soup.triangles[t][0], soup.triangles[t][1], soup.triangles[t][2], l, c[0], c[1], c[2]);
  }
  std::size_t first = soup.points.size();
  for (const auto& l : lines) {
    const std::size_t n = l.points.size();
    for (std::size_t i = 0; i < segment_count(l); ++i)
      fmt::format_to(out, "{} {} {} {} {}\n", first + i, first + (i + 1) % n, l.colour[0], l.colour[1], l.colour[2]);
    first += n;
  }
  return o;
}

std::string obj(const Soup& soup, const std::vector<Polyline>& lines) {
  std::string o;
  auto out = std::back_inserter(o);
  fmt::format_to(out, "# j232 labelled scene: one group per surface label{}\n",
                 lines.empty() ? "" : ", then one per kind of line (tip circles, feed stations, seat, reach envelope, nail paths)");
  for (const auto& p : soup.points) fmt::format_to(out, "v {} {} {}\n", p.x(), p.y(), p.z());
  for (const auto& l : lines)
    for (const auto& p : l.points) fmt::format_to(out, "v {} {} {}\n", p.x(), p.y(), p.z());
  for (int l = 0; l < kSurfaceKinds; ++l) {
    bool any = false;
    for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
      if (static_cast<int>(soup.labels[t]) != l) continue;
      if (!any) fmt::format_to(out, "g {}\n", name(static_cast<Surface>(l)));
      any = true;
      fmt::format_to(out, "f {} {} {}\n", soup.triangles[t][0] + 1, soup.triangles[t][1] + 1, soup.triangles[t][2] + 1);
    }
  }
  std::size_t first = soup.points.size() + 1;  // OBJ counts from 1
  std::string group;
  for (const auto& l : lines) {
    if (segment_count(l)) {
      if (l.group != group) fmt::format_to(out, "g {}\n", l.group), group = l.group;
      fmt::format_to(out, "l");
      for (std::size_t i = 0; i < l.points.size(); ++i) fmt::format_to(out, " {}", first + i);
      if (l.closed && l.points.size() > 2) fmt::format_to(out, " {}", first);
      fmt::format_to(out, "\n");
    }
    first += l.points.size();
  }
  return o;
}
}  // namespace

std::array<std::uint8_t, 3> label_rgb(Surface label) {
  static constexpr std::uint8_t kColour[kSurfaceKinds][3] = {{90, 160, 70},  {140, 140, 140}, {60, 90, 200},
                                                            {140, 90, 40}, {235, 235, 225}, {220, 40, 40}};
  const auto& c = kColour[static_cast<std::size_t>(label)];
  return {c[0], c[1], c[2]};
}

std::string export_text(const Soup& soup, const std::vector<Polyline>& lines, const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".ply") return ply(soup, lines);
  if (ext == ".obj") return obj(soup, lines);
  throw std::invalid_argument(fmt::format("{}: export format must be .ply or .obj", path));
}

}  // namespace j232::scene
