// The only translation unit that sees CGAL's AABB tree (slow to compile, so kept out of every other file).
#include "scene/scene.hpp"

#include "scene/ray_triangle.hpp"
#include "scene/box_tree.hpp"

#include <cmath>
#include <utility>
#ifdef J232_HAVE_EMBREE
#include "scene/embree_index.hpp"
#endif

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

// CGAL's index: the triangles as a face graph (the AABB tree's primitives), each face
// mapped back to its soup triangle.
struct CgalIndex {
  Mesh mesh;
  std::vector<std::uint32_t> soup_face;  // mesh face index -> soup triangle
  Tree tree;

  explicit CgalIndex(const Soup& soup) {
    std::vector<Mesh::Vertex_index> vertex;
    vertex.reserve(soup.points.size());
    auto point = [&](std::uint32_t i) { return Point(soup.points[i].x(), soup.points[i].y(), soup.points[i].z()); };
    for (std::uint32_t i = 0; i < soup.points.size(); ++i) vertex.push_back(mesh.add_vertex(point(i)));
    for (std::uint32_t t = 0; t < soup.triangles.size(); ++t) {
      const auto& tri = soup.triangles[t];
      FaceIndex f = mesh.add_face(vertex[tri[0]], vertex[tri[1]], vertex[tri[2]]);
      if (f == Mesh::null_face())  // non-manifold where it meets the others: its own corners (a tree needs triangles, not a manifold)
        f = mesh.add_face(mesh.add_vertex(point(tri[0])), mesh.add_vertex(point(tri[1])), mesh.add_vertex(point(tri[2])));
      if (f == Mesh::null_face()) throw std::invalid_argument(fmt::format("face {} could not be added to the mesh", t + 1));
      if (soup_face.size() <= f.idx()) soup_face.resize(f.idx() + 1, Skip::kNone);
      soup_face[f.idx()] = t;
    }
    tree.insert(faces(mesh).first, faces(mesh).second, mesh);
    tree.build();
  }
};

// Closest-hit search over CGAL's AABB tree without allocating: CGAL's own
// first_intersection keeps a heap-allocated priority queue, and this runs many times for
// every nail. traversal_with_priority visits the nearer child first; boxes beyond the best
// hit so far are pruned; the exact test of ray_triangle.hpp decides each triangle.
struct ClosestHit {
  const std::vector<TriangleEdges>* triangles;
  const std::vector<std::uint32_t>* soup_face;
  const Skip* skip;
  NearestHit* best;
  using Priority = double;

  bool go_further() const { return true; }

  // Entry distance of the ray into a box, or nothing when it misses within [0, best]
  // (widened a little: a face as near as the best still counts, by the tie rule).
  bool slab(const RayQuery& q, const CGAL::Bbox_3& b, double& entry) const {
    double t0 = 0.0, t1 = best->distance;
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
  template <class P>
  void intersection(const RayQuery& q, const P& primitive) {
    const std::uint32_t f = (*soup_face)[primitive.id().idx()];
    best->offer(q, (*triangles)[f], f, *skip);
  }
};

// Consecutive triangles t = (a, b, c), t + 1 = (a, c, d) that make one flat, convex
// quadrilateral a-b-c-d with one label and one guard (Soup::add_quad's panels): each as a
// Scene::Quad, with its first triangle's number. Flat: d within 1e-12 of the quad's size of
// (a, b, c)'s plane and both normals alike; convex: every corner turns the same way.
void find_quads(const Soup& soup, const std::vector<Vec3>& normals, const std::vector<Scene::Gram>& grams, const std::vector<bool>& taken,
                std::vector<Scene::Quad>& quads, std::vector<std::uint32_t>& first) {
  for (std::uint32_t t = 0; t + 1 < soup.triangles.size(); ++t) {
    if (taken[t] || taken[t + 1]) continue;
    const auto &p = soup.triangles[t], &q = soup.triangles[t + 1];
    if (!(q[0] == p[0] && q[1] == p[2])) continue;
    if (soup.labels[t] != soup.labels[t + 1] || soup.guard_index[t] != soup.guard_index[t + 1]) continue;
    const std::array<Vec3, 4> corner{soup.points[p[0]], soup.points[p[1]], soup.points[p[2]], soup.points[q[2]]};
    const Vec3& n = normals[t];
    double size = 0;
    for (const Vec3& c : corner) size = std::max(size, (c - corner[0]).norm());
    if (!(normals[t + 1].dot(n) > 1 - 1e-12) || !(std::abs(n.dot(corner[3] - corner[0])) <= 1e-12 * size)) continue;
    Scene::Quad quad;
    bool convex = true;
    for (std::size_t i = 0; i < 4; ++i) {
      quad.corner[i] = corner[i], quad.edge[i] = corner[(i + 1) % 4] - corner[i];
      const Vec3 next = corner[(i + 2) % 4] - corner[(i + 1) % 4];
      convex = convex && quad.edge[i].cross(next).dot(n) > 0;
      quad.inward[i] = n.cross(quad.edge[i]).normalized();  // (the corners run counterclockwise about n)
    }
    if (!convex) continue;
    quad.normal = grams[t].normal, quad.nn = grams[t].nn;
    quads.push_back(quad), first.push_back(t);
    ++t;  // the second triangle is taken
  }
}

// Runs of consecutive triangles (c, p_0, p_1), (c, p_1, p_2), ..., (c, p_K-1, p_0), K >= 3,
// fanned from one point c round a closed rim, one label and one guard (a deck's plate: a disc,
// or an outline fanned from its centroid): each, when flat and convex, as a Scene::Polygon with
// its first triangle's number and its count. Points are matched by position (an outline's
// triangles each add their own corners). Flat: every triangle's normal the first's to 1e-12 and
// every corner within 1e-12 of the rim's size of its plane (so c lies inside, every triangle
// turning the same way); convex: no corner turns back beyond rounding; the corners' angles
// about c then rise strictly round the rim.
struct PolygonRun {
  std::uint32_t first_triangle;
  std::size_t count;
  Vec3 centre, u, v;
  std::size_t least;  // the corner of the least angle
};
void find_polygons(const Soup& soup, const std::vector<Vec3>& normals, std::vector<PolygonRun>& runs, std::vector<Vec3>& corners,
                   std::vector<double>& angles) {
  const auto point = [&](std::uint32_t t, int k) -> const Vec3& { return soup.points[soup.triangles[t][static_cast<std::size_t>(k)]]; };
  const std::uint32_t n_tri = static_cast<std::uint32_t>(soup.triangles.size());
  for (std::uint32_t t = 0; t < n_tri; ++t) {
    const Vec3& c = point(t, 0);
    std::uint32_t end = t + 1;  // one past the run's last triangle, once it closes
    bool closed = false;
    for (std::uint32_t k = t + 1; k < n_tri; ++k) {
      if (!(point(k, 0) == c && point(k, 1) == point(k - 1, 2)) || soup.labels[k] != soup.labels[t] || soup.guard_index[k] != soup.guard_index[t]) break;
      if (k - t + 1 >= 3 && point(k, 2) == point(t, 1)) {
        end = k + 1, closed = true;
        break;
      }
    }
    if (!closed) continue;
    const std::size_t K = end - t;
    const Vec3& n = normals[t];
    double size = 0;
    for (std::uint32_t k = t; k < end; ++k) size = std::max(size, (point(k, 1) - c).norm());
    bool flat = true;
    for (std::uint32_t k = t; k < end && flat; ++k) flat = normals[k].dot(n) > 1 - 1e-12 && std::abs(n.dot(point(k, 1) - c)) <= 1e-12 * size;
    if (!flat) continue;
    bool convex = true;
    for (std::size_t i = 0; i < K && convex; ++i) {
      const Vec3& a = point(t + static_cast<std::uint32_t>(i), 1);
      const Vec3& b = point(t + static_cast<std::uint32_t>((i + 1) % K), 1);
      const Vec3& d = point(t + static_cast<std::uint32_t>((i + 2) % K), 1);
      convex = (b - a).cross(d - b).dot(n) >= -1e-12 * (b - a).norm() * (d - b).norm();
    }
    if (!convex) continue;
    PolygonRun run{t, K, c, Vec3::Zero(), Vec3::Zero(), 0};
    const Vec3 first = point(t, 1) - c;
    run.u = (first - n.dot(first) * n).normalized(), run.v = n.cross(run.u);
    std::vector<double> angle(K);
    for (std::size_t i = 0; i < K; ++i) {
      const Vec3 r = point(t + static_cast<std::uint32_t>(i), 1) - c;
      angle[i] = std::atan2(r.dot(run.v), r.dot(run.u));
      if (angle[i] < angle[run.least]) run.least = i;
    }
    bool rising = true;
    for (std::size_t k = 0; k + 1 < K && rising; ++k) rising = angle[(run.least + k) % K] < angle[(run.least + k + 1) % K];
    if (!rising) continue;
    for (std::size_t i = 0; i < K; ++i) corners.push_back(point(t + static_cast<std::uint32_t>(i), 1));
    for (std::size_t k = 0; k < K; ++k) angles.push_back(angle[(run.least + k) % K]);
    runs.push_back(run);
    t = end - 1;  // the run's triangles are taken
  }
}

// A sphere about the corners' centroid holding them all (so the whole flat convex face).
Scene::Ball ball_about(const Vec3* corner, std::size_t count) {
  Vec3 centre = Vec3::Zero();
  for (std::size_t i = 0; i < count; ++i) centre += corner[i];
  centre /= static_cast<double>(count);
  double radius = 0;
  for (std::size_t i = 0; i < count; ++i) radius = std::max(radius, (corner[i] - centre).norm());
  return {centre, radius * (1 + 1e-12) + 1e-15};
}

}  // namespace

bool engine_available(Engine e) {
#ifdef J232_HAVE_EMBREE
  (void)e;
  return true;
#else
  return e == Engine::Cgal;
#endif
}

Engine default_engine() { return engine_available(Engine::Embree) ? Engine::Embree : Engine::Cgal; }

const char* engine_name(Engine e) { return e == Engine::Embree ? "embree" : "cgal"; }

struct Scene::Impl {
  Soup soup;
  Engine engine = Engine::Cgal;
  std::vector<Vec3> normals;             // per soup triangle, unit
  std::vector<TriangleEdges> triangles;  // per soup triangle: corner, two edges
  std::vector<Scene::Ball> balls;        // per soup triangle: a sphere holding it
  std::vector<Scene::Gram> grams;        // per soup triangle: its nearest-point constants
  std::vector<Box> boxes;                // per soup triangle: its box, from the corner and edges as the queries see it
  std::vector<Scene::Quad> quads;        // the quads found (two triangles each)
  std::vector<const Scene::Quad*> quad_of;  // per soup triangle: its quad when it leads one, else null
  std::vector<Scene::Polygon> polygons;  // the closed fans found (a plate)
  std::vector<const Scene::Polygon*> polygon_of;  // per soup triangle: its polygon when it leads one, else null
  std::vector<Vec3> polygon_corners, polygon_edges, polygon_inward;  // every polygon's, one after another
  std::vector<double> polygon_angles;
  std::vector<std::uint32_t> searched;   // the faces the broad phase lists: triangles alone and each quad's and polygon's first
  std::vector<Box> searched_boxes;       // their boxes (a quad's holds both triangles)
  std::unique_ptr<BoxTree> box_tree;     // over `searched_boxes`: the broad phase
  std::unique_ptr<CgalIndex> cgal;
#ifdef J232_HAVE_EMBREE
  std::unique_ptr<EmbreeIndex> embree;
#endif
};

Scene::Scene(Soup soup, Engine engine) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.soup = std::move(soup);
  m.engine = engine;
  if (!engine_available(engine))
    throw std::runtime_error(fmt::format("the {} scene engine is not built into this j232 (Embree 3 was not found when it was configured)",
                                         engine_name(engine)));
  if (m.soup.triangles.empty()) throw std::invalid_argument("the scene has no faces");
  for (std::uint32_t t = 0; t < m.soup.triangles.size(); ++t) {
    const auto& tri = m.soup.triangles[t];
    const Vec3 n = (m.soup.points[tri[1]] - m.soup.points[tri[0]]).cross(m.soup.points[tri[2]] - m.soup.points[tri[0]]);
    const double scale =
        (m.soup.points[tri[1]] - m.soup.points[tri[0]]).squaredNorm() + (m.soup.points[tri[2]] - m.soup.points[tri[0]]).squaredNorm();
    if (!(n.norm() > 1e-12 * scale) || !(scale > 0)) throw std::invalid_argument(fmt::format("face {} is degenerate (zero area)", t + 1));
    m.normals.push_back(n.normalized());
    m.triangles.push_back(
        {m.soup.points[tri[0]], m.soup.points[tri[1]] - m.soup.points[tri[0]], m.soup.points[tri[2]] - m.soup.points[tri[0]]});
    const Vec3 centroid = (m.soup.points[tri[0]] + m.soup.points[tri[1]] + m.soup.points[tri[2]]) / 3.0;
    double radius = 0;
    for (int k = 0; k < 3; ++k) radius = std::max(radius, (m.soup.points[tri[static_cast<std::size_t>(k)]] - centroid).norm());
    m.balls.push_back({centroid, radius * (1 + 1e-12) + 1e-15});
    const TriangleEdges& e = m.triangles.back();
    m.grams.push_back(Scene::Gram::of(e));
    const Vec3 b = e[0] + e[1], c = e[0] + e[2];
    m.boxes.push_back({e[0].cwiseMin(b).cwiseMin(c), e[0].cwiseMax(b).cwiseMax(c)});
  }
  // Closed fans first (their triangles, two at a time, would pass for quads), then quads of
  // what is left.
  std::vector<PolygonRun> runs;
  find_polygons(m.soup, m.normals, runs, m.polygon_corners, m.polygon_angles);
  std::vector<bool> second(m.soup.triangles.size(), false), taken(m.soup.triangles.size(), false);
  m.polygon_of.assign(m.soup.triangles.size(), nullptr);
  // (Reserved whole, so that the polygons' pointers into them stay valid.)
  m.polygons.reserve(runs.size());
  m.polygon_edges.reserve(m.polygon_corners.size()), m.polygon_inward.reserve(m.polygon_corners.size());
  for (std::size_t offset = 0; const PolygonRun& run : runs) {
    const std::uint32_t t = run.first_triangle;
    const std::size_t K = run.count;
    for (std::size_t i = 0; i < K; ++i) {
      const Vec3 edge = m.polygon_corners[offset + (i + 1) % K] - m.polygon_corners[offset + i];
      m.polygon_edges.push_back(edge);
      m.polygon_inward.push_back(m.normals[t].cross(edge).normalized());
    }
    m.polygons.push_back({m.polygon_corners.data() + offset, m.polygon_edges.data() + offset, m.polygon_inward.data() + offset,
                          m.polygon_angles.data() + offset, K, run.least, run.centre, run.u, run.v, m.grams[t].normal, m.grams[t].nn});
    m.polygon_of[t] = &m.polygons.back();
    m.balls[t] = ball_about(m.polygons.back().corner, K);
    for (std::size_t i = 0; i < K; ++i) taken[t + i] = true, second[t + i] = i > 0;
    offset += K;
  }
  std::vector<std::uint32_t> quad_first;  // each quad's first triangle
  find_quads(m.soup, m.normals, m.grams, taken, m.quads, quad_first);
  m.quad_of.assign(m.soup.triangles.size(), nullptr);
  for (std::size_t i = 0; i < m.quads.size(); ++i) {
    const std::uint32_t t = quad_first[i];
    m.quad_of[t] = &m.quads[i], second[t + 1] = true;
    m.balls[t] = ball_about(m.quads[i].corner.data(), 4);
  }
  for (std::uint32_t t = 0; t < m.soup.triangles.size(); ++t) {
    if (second[t]) continue;
    Box box = m.boxes[t];
    if (m.quad_of[t]) box.lo = box.lo.cwiseMin(m.boxes[t + 1].lo), box.hi = box.hi.cwiseMax(m.boxes[t + 1].hi);
    if (const Scene::Polygon* poly = m.polygon_of[t])
      for (std::size_t i = 1; i < poly->count; ++i) box.lo = box.lo.cwiseMin(m.boxes[t + i].lo), box.hi = box.hi.cwiseMax(m.boxes[t + i].hi);
    m.searched.push_back(t), m.searched_boxes.push_back(box);
  }
  m.box_tree = std::make_unique<BoxTree>(m.searched_boxes);
  faces_ = {m.triangles.data(), m.normals.data(), m.grams.data(), m.balls.data(), m.quad_of.data(), m.polygon_of.data()};
#ifdef J232_HAVE_EMBREE
  if (engine == Engine::Embree) {
    m.embree = std::make_unique<EmbreeIndex>(m.triangles);
    return;
  }
#endif
  m.cgal = std::make_unique<CgalIndex>(m.soup);
}

Scene::~Scene() = default;
Scene::Scene(Scene&& o) noexcept : impl_(std::move(o.impl_)), faces_(std::exchange(o.faces_, {})) {}
Scene& Scene::operator=(Scene&& o) noexcept {
  impl_ = std::move(o.impl_), faces_ = std::exchange(o.faces_, {});
  return *this;
}

namespace {
// The faces met, kept in increasing face order (the search's results must not depend on
// the order a tree visits them in); beyond `capacity`, the lowest-numbered ones, so that
// what is kept does not depend on it either.
struct BoxCollector {
  std::uint32_t* out;
  std::size_t capacity, count = 0;
  void operator()(std::uint32_t f) {
    ++count;
    if (capacity == 0) return;
    std::size_t i = count - 1;  // insertion keeps the order (the lists are short)
    if (i >= capacity) {        // full: f takes the highest one's place if it is lower
      if (out[capacity - 1] < f) return;
      i = capacity - 1;
    }
    while (i > 0 && out[i - 1] > f) out[i] = out[i - 1], --i;
    out[i] = f;
  }
};
}  // namespace

// One box tree for both engines: neither Embree's point query (a sphere around the box) nor
// CGAL's tree is as cheap for a box against boxes, and one structure gives one list.
std::size_t Scene::faces_in_box(const Vec3& lo, const Vec3& hi, std::uint32_t* out, std::size_t capacity) const {
  const Impl& m = *impl_;
  BoxCollector collect{out, capacity};
  m.box_tree->visit(m.searched_boxes, lo, hi, [&](std::uint32_t i) { collect(m.searched[i]); });
  return collect.count;
}


const Soup& Scene::soup() const { return impl_->soup; }
std::size_t Scene::face_count() const { return impl_->soup.triangles.size(); }
Engine Scene::engine() const { return impl_->engine; }

std::optional<Hit> Scene::first_hit(const Vec3& from, const Vec3& dir, double max_distance, const Skip& skip) const {
  const Impl& m = *impl_;
  const RayQuery q(from, dir);
  NearestHit best{max_distance};
#ifdef J232_HAVE_EMBREE
  if (m.embree) m.embree->closest(q, skip, best);
#endif
  if (m.cgal) {
    ClosestHit search{&m.triangles, &m.cgal->soup_face, &skip, &best};
    m.cgal->tree.traversal_with_priority(q, search);
  }
  if (best.face == Skip::kNone) return std::nullopt;
  Hit h;
  h.distance = best.distance;
  h.point = from + best.distance * dir;
  h.face = best.face;
  h.surface = m.soup.labels[h.face];
  h.guard = m.soup.guard_index[h.face];
  h.normal = m.normals[h.face].dot(dir) > 0 ? Vec3(-m.normals[h.face]) : m.normals[h.face];
  return h;
}

}  // namespace j232::scene
