// The only translation unit that sees CGAL's AABB tree (slow to compile; DESIGN.md §5).
#include "scene/scene.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <fmt/format.h>
#include <stdexcept>

namespace j232::scene {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using FaceIndex = Mesh::Face_index;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
}  // namespace

struct Scene::Impl {
  Soup soup;
  Mesh mesh;
  std::vector<std::uint32_t> soup_face;  // mesh face index -> soup triangle
  std::vector<Vec3> normals;             // per soup triangle, unit
  Tree tree;
};

Scene::Scene(Soup soup) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.soup = std::move(soup);
  if (m.soup.triangles.empty()) throw std::invalid_argument("the scene has no faces");
  std::vector<Mesh::Vertex_index> vertex;
  vertex.reserve(m.soup.points.size());
  for (const Vec3& p : m.soup.points) vertex.push_back(m.mesh.add_vertex(Point(p.x(), p.y(), p.z())));
  auto label = m.mesh.add_property_map<FaceIndex, std::uint8_t>("f:label", 0).first;
  for (std::uint32_t t = 0; t < m.soup.triangles.size(); ++t) {
    const auto& tri = m.soup.triangles[t];
    const Vec3 n = (m.soup.points[tri[1]] - m.soup.points[tri[0]]).cross(m.soup.points[tri[2]] - m.soup.points[tri[0]]);
    const double scale = (m.soup.points[tri[1]] - m.soup.points[tri[0]]).squaredNorm() +
                         (m.soup.points[tri[2]] - m.soup.points[tri[0]]).squaredNorm();
    if (!(n.norm() > 1e-12 * scale) || !(scale > 0))
      throw std::invalid_argument(fmt::format("face {} is degenerate (zero area)", t + 1));
    m.normals.push_back(n.normalized());
    FaceIndex f = m.mesh.add_face(vertex[tri[0]], vertex[tri[1]], vertex[tri[2]]);
    if (f == Mesh::null_face()) {
      // Non-manifold where this triangle meets the others: give it its own corners.
      // Ray queries need triangles, not a manifold.
      f = m.mesh.add_face(m.mesh.add_vertex(Point(m.soup.points[tri[0]].x(), m.soup.points[tri[0]].y(), m.soup.points[tri[0]].z())),
                          m.mesh.add_vertex(Point(m.soup.points[tri[1]].x(), m.soup.points[tri[1]].y(), m.soup.points[tri[1]].z())),
                          m.mesh.add_vertex(Point(m.soup.points[tri[2]].x(), m.soup.points[tri[2]].y(), m.soup.points[tri[2]].z())));
    }
    if (f == Mesh::null_face()) throw std::invalid_argument(fmt::format("face {} could not be added to the mesh", t + 1));
    label[f] = static_cast<std::uint8_t>(m.soup.labels[t]);
    if (m.soup_face.size() <= f.idx()) m.soup_face.resize(f.idx() + 1, Skip::kNone);
    m.soup_face[f.idx()] = t;
  }
  m.tree.insert(faces(m.mesh).first, faces(m.mesh).second, m.mesh);
  m.tree.build();
}

Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

const Soup& Scene::soup() const { return impl_->soup; }
std::size_t Scene::face_count() const { return impl_->soup.triangles.size(); }

double Scene::face_area(std::uint32_t face) const {
  const auto& s = impl_->soup;
  const auto& t = s.triangles.at(face);
  return 0.5 * (s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]]).norm();
}

Vec3 Scene::face_centroid(std::uint32_t face) const {
  const auto& s = impl_->soup;
  const auto& t = s.triangles.at(face);
  return (s.points[t[0]] + s.points[t[1]] + s.points[t[2]]) / 3.0;
}

std::optional<Hit> Scene::first_hit(const Vec3& from, const Vec3& dir, double max_distance, const Skip& skip_in) const {
  const Impl& m = *impl_;
  Skip skip = skip_in;
  const Kernel::Ray_3 ray(Point(from.x(), from.y(), from.z()), Kernel::Vector_3(dir.x(), dir.y(), dir.z()));
  // A ray leaving a surface can graze a neighbouring face at distance ~0 where two faces
  // meet; skip such hits and ask again (a few times at most).
  for (int attempt = 0; attempt < 4; ++attempt) {
    const auto result = m.tree.first_intersection(
        ray, [&](FaceIndex f) { return skip.contains(m.soup_face[f.idx()]); });
    if (!result) return std::nullopt;
    Vec3 point;
    if (const Point* p = boost::get<Point>(&result->first)) {
      point = {p->x(), p->y(), p->z()};
    } else if (const auto* seg = boost::get<Kernel::Segment_3>(&result->first)) {
      // The ray runs within the face's plane: take its nearer end.
      const Point a = seg->source(), b = seg->target();
      const Vec3 pa(a.x(), a.y(), a.z()), pb(b.x(), b.y(), b.z());
      point = (pa - from).dot(dir) < (pb - from).dot(dir) ? pa : pb;
    } else {
      return std::nullopt;
    }
    const std::uint32_t face = m.soup_face[result->second.idx()];
    const double distance = (point - from).dot(dir);
    if (distance > max_distance) return std::nullopt;
    if (distance < 1e-9) {
      skip.add(face);
      continue;
    }
    Hit h;
    h.distance = distance;
    h.point = point;
    h.face = face;
    h.surface = m.soup.labels[face];
    h.guard = m.soup.guard_index[face];
    h.normal = m.normals[face].dot(dir) > 0 ? Vec3(-m.normals[face]) : m.normals[face];
    return h;
  }
  return std::nullopt;
}

}  // namespace j232::scene
