#pragma once
// The scene a thrown nail flies through: labelled triangles indexed for first-hit ray
// queries (docs/model.md §5.3–5.4) by CGAL's AABB tree or Embree's BVH. CGAL stays inside
// scene.cpp and Embree inside embree_index.cpp; this header is all the rest of the
// program sees.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "scene/soup.hpp"

namespace j232::scene {

struct Hit {
  double distance = 0;  // along the ray, m
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // unit, facing back against the ray
  Surface surface = Surface::Ground;
  std::uint32_t face = 0;
  std::uint16_t guard = 0;
};

// Faces a query must not report (the one a nail just left, and neighbours met at an edge).
struct Skip {
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  std::uint32_t faces[4] = {kNone, kNone, kNone, kNone};
  bool contains(std::uint32_t f) const { return f == faces[0] || f == faces[1] || f == faces[2] || f == faces[3]; }
  void add(std::uint32_t f) {
    for (auto& slot : faces)
      if (slot == kNone) {
        slot = f;
        return;
      }
    faces[3] = f;
  }
};

// Which index chooses the triangles a ray query tests: CGAL's AABB tree (the reference)
// or Embree's BVH (faster; built in when Embree 3 is found at configure time). The same
// exact double-precision test decides every hit, so both give the same answers.
enum class Engine { Cgal, Embree };
bool engine_available(Engine e);
Engine default_engine();            // Embree when built in
const char* engine_name(Engine e);  // "cgal", "embree"

class Scene {
 public:
  // Throws std::invalid_argument for an empty scene or a degenerate (zero-area) face, and
  // std::runtime_error when the engine is not built in.
  explicit Scene(Soup soup, Engine engine = default_engine());
  ~Scene();
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;

  // First surface along from + t dir, 0 < t <= max_distance (dir: unit vector). Among
  // faces hit at the same distance, the lowest face number.
  std::optional<Hit> first_hit(const Vec3& from, const Vec3& dir, double max_distance, const Skip& skip = {}) const;

  // The faces whose bounding boxes meet the box [lo, hi] (the broad phase of the capsule's
  // contact search, flight/face_touch.hpp; a quad once, by its first triangle), in increasing face order, decided exactly in
  // double precision so that both engines give the same list. Writes at most `capacity`
  // of them to `out` (the lowest-numbered, when there are more) and returns how many there
  // are (more than `capacity`: the caller asks again over a smaller box). Allocation-free.
  std::size_t faces_in_box(const Vec3& lo, const Vec3& hi, std::uint32_t* out, std::size_t capacity) const;
  // Face f as its first corner and two edges from it, and its unit normal (either side).
  // (These four are inline: the contact search reads them millions of times a second.)
  const std::array<Vec3, 3>& face_edges(std::uint32_t f) const { return faces_.edges[f]; }
  const Vec3& face_normal(std::uint32_t f) const { return faces_.normals[f]; }
  // Face f's constants for nearest-point tests (flight::segment_triangle), worked out once
  // with the scene instead of at every test: the unnormalised normal e1 x e2 and its squared
  // length, and the edges' Gram matrix [d00 d01; d01 d11] with its determinant.
  struct Gram {
    Vec3 normal;
    double nn, d00, d01, d11, det;
    static Gram of(const std::array<Vec3, 3>& edges) {
      Gram g;
      const Vec3 &e1 = edges[1], &e2 = edges[2];
      g.normal = e1.cross(e2);
      g.nn = g.normal.squaredNorm();
      g.d00 = e1.squaredNorm(), g.d01 = e1.dot(e2), g.d11 = e2.squaredNorm();
      g.det = g.d00 * g.d11 - g.d01 * g.d01;
      return g;
    }
  };
  const Gram& face_gram(std::uint32_t f) const { return faces_.grams[f]; }
  // A sphere holding face f (its centroid, and the farthest corner's distance from it).
  struct Ball {
    Vec3 centre;
    double radius;
  };
  const Ball& face_ball(std::uint32_t f) const { return faces_.balls[f]; }
  // Two triangles of one flat, convex quadrilateral (a panel the scene was built of, as
  // Soup::add_quad gives it: (a, b, c) then (a, c, d), coplanar, one label, one guard) are
  // one face to the contact search: its corners in order (counterclockwise about `normal`),
  // the outer edges from each corner to the next, each edge's unit normal in the plane
  // pointing inside, and the first triangle's unnormalised normal (its Gram normal) with its
  // squared length. The quad is numbered by its first triangle; the second is never listed
  // by faces_in_box, and face_ball of the first holds both. Null for a face that is a
  // triangle alone.
  struct Quad {
    std::array<Vec3, 4> corner, edge, inward;
    Vec3 normal;
    double nn;
  };
  const Quad* face_quad(std::uint32_t f) const { return faces_.quads[f]; }
  // A closed fan of triangles (c, p_k, p_k+1), k = 0..K-1, from one inner point c round a flat,
  // convex rim back to p_0, one label and guard (a deck's plate: a disc, or an outline fanned
  // from its centroid) is one face to the contact search likewise: its rim's corners in order
  // (counterclockwise about `normal`), each outer edge to the next corner with its unit normal
  // in the plane pointing inside, each corner's angle about c in the plane's basis (u, v) (from
  // -pi, increasing), and the first triangle's unnormalised normal with its squared length.
  // Numbered by its first triangle; the others are never listed by faces_in_box, and face_ball
  // of the first holds the whole polygon. Null for a face that is no such fan.
  struct Polygon {
    const Vec3* corner;
    const Vec3* edge;
    const Vec3* inward;
    const double* angle;  // sorted: the corners rotated so that the first has the least angle
    std::size_t count;
    std::size_t first;  // the corner of the least angle (angle[k] is corner[(first + k) % count]'s)
    Vec3 centre, u, v, normal;
    double nn;
  };
  const Polygon* face_polygon(std::uint32_t f) const { return faces_.polygons[f]; }

  const Soup& soup() const;
  std::size_t face_count() const;
  Engine engine() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  // The per-face arrays Impl keeps (they move with it).
  struct FaceArrays {
    const std::array<Vec3, 3>* edges = nullptr;
    const Vec3* normals = nullptr;
    const Gram* grams = nullptr;
    const Ball* balls = nullptr;
    const Quad* const* quads = nullptr;
    const Polygon* const* polygons = nullptr;
  } faces_;
};

// The labelled scene for a mesh viewer, as the text of a file named `path`: .ply (face
// property "label" and a colour per label; the lines as PLY edges with a colour) or .obj
// (one group per label, then one per group of lines, as OBJ line elements). Throws
// std::invalid_argument for another extension.
std::string export_text(const Soup& soup, const std::vector<Polyline>& lines, const std::string& path);
// The colour a viewer shows a label in (the export's, and the 3D view's): ground green,
// housing grey, deflector blue, guard brown, target white, operator zone red.
std::array<std::uint8_t, 3> label_rgb(Surface label);

}  // namespace j232::scene
