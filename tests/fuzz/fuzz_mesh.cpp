// libFuzzer target: each mesh reader (OBJ, OFF, PLY, STL; the first byte picks one).
// A malformed mesh must be refused with std::runtime_error naming the file; a mesh
// that is read must hold only finite, in-range vertices and valid triangles.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "scene/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* kExtensions[] = {".obj", ".off", ".ply", ".stl"};
  const std::string path = "/tmp/j232-fuzz-mesh-" + std::to_string(::getpid()) + kExtensions[data[0] % 4];
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  try {
    const auto soup = j232::scene::read_mesh(path, j232::scene::Surface::Housing, 1.0);
    for (const auto& p : soup.points)
      if (!p.allFinite() || p.norm() > j232::scene::kMaxSceneRadius) std::abort();
    for (const auto& t : soup.triangles)
      for (auto v : t)
        if (v >= soup.points.size()) std::abort();
  } catch (const std::runtime_error&) {
  }
  std::remove(path.c_str());
  return 0;
}
