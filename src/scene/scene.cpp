// The only translation unit that sees CGAL's AABB tree (slow to compile, so kept out of every other file).
#include "scene/scene.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <fmt/format.h>
#include <cmath>
#include <limits>
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
  std::vector<std::array<Vec3, 3>> triangles;  // per soup triangle: corner, two edges
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
    m.triangles.push_back({m.soup.points[tri[0]], m.soup.points[tri[1]] - m.soup.points[tri[0]],
                           m.soup.points[tri[2]] - m.soup.points[tri[0]]});
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

namespace {

// A ray for the traversal below, with what the slab test needs precomputed.
struct RayQuery {
  Vec3 origin, dir, inverse;
};

// Closest-hit search over CGAL's AABB tree without allocating: CGAL's own
// first_intersection keeps a heap-allocated priority queue, and this runs a few times for
// every nail. traversal_with_priority visits the nearer child first; boxes beyond the best
// hit so far are pruned; triangles are tested with Moller-Trumbore.
struct ClosestHit {
  const std::vector<std::array<Vec3, 3>>* triangles;  // p0, e1, e2 per soup triangle
  const std::vector<std::uint32_t>* soup_face;
  const Skip* skip;
  double best;
  std::uint32_t face = Skip::kNone;
  using Priority = double;

  bool go_further() const { return true; }

  // Entry distance of the ray into a box, or nothing when it misses within [0, best].
  bool slab(const RayQuery& q, const CGAL::Bbox_3& b, double& entry) const {
    double t0 = 0.0, t1 = best;
    const double lo[3] = {b.xmin(), b.ymin(), b.zmin()}, hi[3] = {b.xmax(), b.ymax(), b.zmax()};
    for (int a = 0; a < 3; ++a) {
      double near = (lo[a] - q.origin[a]) * q.inverse[a], far = (hi[a] - q.origin[a]) * q.inverse[a];
      if (near > far) std::swap(near, far);
      if (std::isnan(near) || std::isnan(far)) {  // parallel to the slab: inside it or not
        if (q.origin[a] < lo[a] || q.origin[a] > hi[a]) return false;
        continue;
      }
      t0 = std::max(t0, near);
      t1 = std::min(t1, far * (1 + 4 * std::numeric_limits<double>::epsilon()));
      if (t0 > t1) return false;
    }
    entry = t0;
    return true;
  }
  template <class Node>
  bool do_intersect(const RayQuery& q, const Node& node) const {
    double entry;
    return slab(q, node.bbox(), entry);
  }
  template <class Node>
  std::pair<bool, Priority> do_intersect_with_priority(const RayQuery& q, const Node& node) const {
    double entry = 0;
    const bool hit = slab(q, node.bbox(), entry);
    return {hit, -entry};
  }
  template <class Primitive>
  void intersection(const RayQuery& q, const Primitive& primitive) {
    const std::uint32_t f = (*soup_face)[primitive.id().idx()];
    if (skip->contains(f)) return;
    const auto& t = (*triangles)[f];
    const Vec3 p = q.dir.cross(t[2]);
    const double det = t[1].dot(p);
    if (std::abs(det) < 1e-300) return;  // the ray runs within the triangle's plane
    const double inv = 1.0 / det;
    const Vec3 s = q.origin - t[0];
    const double u = s.dot(p) * inv;
    if (u < -1e-12 || u > 1 + 1e-12) return;
    const Vec3 qv = s.cross(t[1]);
    const double v = q.dir.dot(qv) * inv;
    if (v < -1e-12 || u + v > 1 + 1e-12) return;
    const double distance = t[2].dot(qv) * inv;
    // Hits at ~0 are the surface being left, or a neighbour met at the same edge.
    if (distance > 1e-9 && distance <= best) {
      best = distance;
      face = f;
    }
  }
};

}  // namespace

std::optional<Hit> Scene::first_hit(const Vec3& from, const Vec3& dir, double max_distance, const Skip& skip) const {
  const Impl& m = *impl_;
  const RayQuery q{from, dir, Vec3(1.0 / dir.x(), 1.0 / dir.y(), 1.0 / dir.z())};
  ClosestHit search{&m.triangles, &m.soup_face, &skip, max_distance};
  m.tree.traversal_with_priority(q, search);
  if (search.face == Skip::kNone) return std::nullopt;
  Hit h;
  h.distance = search.best;
  h.point = from + search.best * dir;
  h.face = search.face;
  h.surface = m.soup.labels[h.face];
  h.guard = m.soup.guard_index[h.face];
  h.normal = m.normals[h.face].dot(dir) > 0 ? Vec3(-m.normals[h.face]) : m.normals[h.face];
  return h;
}

}  // namespace j232::scene
