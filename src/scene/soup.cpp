#include "scene/soup.hpp"

namespace j232::scene {

std::string_view name(Surface s) {
  switch (s) {
    case Surface::Ground: return "ground";
    case Surface::Housing: return "housing";
    case Surface::Deflector: return "deflector";
    case Surface::Guard: return "guard";
    case Surface::TargetOutside: return "target";
    case Surface::TargetZone: return "operator_zone";
  }
  return "unknown";
}

void Soup::append(const Soup& other) {
  const auto base = static_cast<std::uint32_t>(points.size());
  points.insert(points.end(), other.points.begin(), other.points.end());
  for (const auto& t : other.triangles) triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  labels.insert(labels.end(), other.labels.begin(), other.labels.end());
  guard_index.insert(guard_index.end(), other.guard_index.begin(), other.guard_index.end());
}

}  // namespace j232::scene
