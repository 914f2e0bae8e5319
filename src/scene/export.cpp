#include <fmt/format.h>
#include <fmt/os.h>
#include <filesystem>
#include <stdexcept>

#include "scene/scene.hpp"

namespace j232::scene {

namespace {
// Colours a viewer shows per label: ground green, housing grey, deflector blue,
// guard brown, target white, operator zone red.
constexpr int kColour[kSurfaceKinds][3] = {{90, 160, 70}, {140, 140, 140}, {60, 90, 200}, {140, 90, 40}, {235, 235, 225}, {220, 40, 40}};
}  // namespace

void export_scene(const Soup& soup, const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext != ".ply" && ext != ".obj") throw std::runtime_error(fmt::format("{}: export format must be .ply or .obj", path));
  // Write beside the target and rename: no half-written file if interrupted.
  const std::string temp = path + ".partial";
  {
    auto out = fmt::output_file(temp);
    if (ext == ".ply") {
      out.print("ply\nformat ascii 1.0\ncomment j232 labelled scene: label 0 ground, 1 housing, 2 deflector, 3 guard, "
                "4 target, 5 operator_zone\nelement vertex {}\nproperty double x\nproperty double y\nproperty double z\n"
                "element face {}\nproperty list uchar int vertex_indices\nproperty uchar label\n"
                "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n",
                soup.points.size(), soup.triangles.size());
      for (const auto& p : soup.points) out.print("{} {} {}\n", p.x(), p.y(), p.z());
      for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
        const int l = static_cast<int>(soup.labels[t]);
        out.print("3 {} {} {} {} {} {} {}\n", soup.triangles[t][0], soup.triangles[t][1], soup.triangles[t][2], l,
                  kColour[l][0], kColour[l][1], kColour[l][2]);
      }
    } else {
      out.print("# j232 labelled scene: one group per surface label\n");
      for (const auto& p : soup.points) out.print("v {} {} {}\n", p.x(), p.y(), p.z());
      for (int l = 0; l < kSurfaceKinds; ++l) {
        bool any = false;
        for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
          if (static_cast<int>(soup.labels[t]) != l) continue;
          if (!any) out.print("g {}\n", name(static_cast<Surface>(l)));
          any = true;
          out.print("f {} {} {}\n", soup.triangles[t][0] + 1, soup.triangles[t][1] + 1, soup.triangles[t][2] + 1);
        }
      }
    }
  }
  std::filesystem::rename(temp, path);
}

}  // namespace j232::scene
