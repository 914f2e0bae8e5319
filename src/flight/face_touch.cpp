#include "flight/face_touch.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "flight/first_root.hpp"
#include "flight/regula_falsi.hpp"

namespace j232::flight {

namespace {

// The closest pair offered so far (the first of equals kept), into `best`.
struct Nearest {
  SegmentTriangle& best;
  double d2 = HUGE_VAL;
  void offer(const Vec3& ps, const Vec3& pt) {
    const double d = (ps - pt).squaredNorm();
    if (d < d2) d2 = d, best.on_segment = ps, best.on_triangle = pt;
  }
};

// The point of triangle (a, a + e1, a + e2) nearest p, by its Voronoi regions (corners,
// edges, interior).
Vec3 nearest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& ab, const Vec3& ac) {
  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 b = a + ab, bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 c = a + ac, cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// The closest points of segments p1 + s d1 and p2 + t d2 (s, t in [0, 1]).
void nearest_segments(const Vec3& p1, const Vec3& d1, const Vec3& p2, const Vec3& d2, Vec3& c1, Vec3& c2) {
  const Vec3 r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double eps = 1e-30;
  double s = 0, t = 0;
  if (a <= eps && e <= eps) {
    s = t = 0;
  } else if (a <= eps) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= eps) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0, s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  c1 = p1 + s * d1, c2 = p2 + t * d2;
}

}  // namespace

SegmentTriangle segment_triangle(const Vec3& p0, const Vec3& p1, const std::array<Vec3, 3>& tri, const scene::Scene::Gram& g) {
  const Vec3 &a = tri[0], &e1 = tri[1], &e2 = tri[2];
  SegmentTriangle best;
  const Vec3& n = g.normal;
  const double s0 = n.dot(p0 - a), s1 = n.dot(p1 - a);
  // Both ends on one side: when the nearer end's foot on the plane lies inside the
  // triangle, that is the closest pair (no point of the segment is nearer the plane).
  if ((s0 > 0 && s1 > 0) || (s0 < 0 && s1 < 0)) {
    const bool first = std::abs(s0) <= std::abs(s1);
    const Vec3& p = first ? p0 : p1;
    const double sp = first ? s0 : s1, nn = g.nn;
    const Vec3 foot = p - (sp / nn) * n;
    // Barycentric coordinates of the foot.
    const Vec3 w = foot - a;
    const double d00 = g.d00, d01 = g.d01, d11 = g.d11, d20 = w.dot(e1), d21 = w.dot(e2);
    const double denom = g.det;
    const double v = (d11 * d20 - d01 * d21) / denom, u = (d00 * d21 - d01 * d20) / denom;
    if (v >= 0 && u >= 0 && u + v <= 1) {
      best.on_segment = p, best.on_triangle = foot, best.distance = std::abs(sp) / std::sqrt(nn);
      return best;
    }
  }
  // Crossing the triangle's interior: distance 0 there.
  if ((s0 <= 0 && s1 >= 0) || (s0 >= 0 && s1 <= 0)) {
    if (s0 != s1) {
      // Where the segment crosses the plane, in the triangle's barycentric coordinates (with
      // a rounding's margin: a sliver's nearest-point regions are ill-conditioned there).
      const Vec3 x = p0 + (s0 / (s0 - s1)) * (p1 - p0);
      const Vec3 w = x - a;
      const double d00 = g.d00, d01 = g.d01, d11 = g.d11, d20 = w.dot(e1), d21 = w.dot(e2);
      const double denom = g.det;
      const double v = (d11 * d20 - d01 * d21) / denom, u = (d00 * d21 - d01 * d20) / denom;
      constexpr double eps = 1e-12;
      if (v >= -eps && u >= -eps && u + v <= 1 + eps) {
        best.on_segment = x, best.on_triangle = x, best.distance = 0;
        return best;
      }
    }
  }
  Nearest nearest{best};
  nearest.offer(p0, nearest_on_triangle(p0, a, e1, e2));
  if (p1 != p0) {
    nearest.offer(p1, nearest_on_triangle(p1, a, e1, e2));
    const Vec3 d = p1 - p0;
    Vec3 cs, ct;
    nearest_segments(p0, d, a, e1, cs, ct), nearest.offer(cs, ct);
    nearest_segments(p0, d, a, e2, cs, ct), nearest.offer(cs, ct);
    nearest_segments(p0, d, a + e1, e2 - e1, cs, ct), nearest.offer(cs, ct);
  }
  best.distance = std::sqrt(nearest.d2);
  return best;
}

namespace {

constexpr double kNever = std::numeric_limits<double>::quiet_NaN();  // FaceState::exact_at before any check

// The next double above finite t (std::nextafter(t, +inf), without the library call: the
// search's least step, taken hundreds of thousands of times a run).
double next_up(double t) {
  if (t == 0) return std::numeric_limits<double>::denorm_min();
  const auto bits = std::bit_cast<std::uint64_t>(t);
  return std::bit_cast<double>(t > 0 ? bits + 1 : bits - 1);
}

constexpr double kEdgeSlack = 1e-9;  // m: an edge a foot is this close to being beyond is measured too
constexpr double kSlackSpent = 0.1 * kLeavingSlack;  // m: a face being left whose remaining slack lets the capsule move less than this has spent it

// The closest points of a segment and a flat convex face (a quad, a plate's polygon: `Face`
// tells whether a point of its plane is inside it, and offers the candidates beyond the plane's
// own: each end's foot inside, and the edges that can hold the nearest point). n: the face's
// unnormalised normal, nn its squared length, a a point of its plane.
template <class Face>
SegmentTriangle segment_convex(const Vec3& p0, const Vec3& p1, const Vec3& n, double nn, const Vec3& a, const Face& face) {
  SegmentTriangle best;
  const double s0 = n.dot(p0 - a), s1 = n.dot(p1 - a);
  if ((s0 > 0 && s1 > 0) || (s0 < 0 && s1 < 0)) {
    // Both ends on one side: the nearer end's foot inside is the closest pair.
    const bool first = std::abs(s0) <= std::abs(s1);
    const Vec3& p = first ? p0 : p1;
    const double sp = first ? s0 : s1;
    const Vec3 foot = p - (sp / nn) * n;
    if (face.inside(foot, 0.0)) {
      best.on_segment = p, best.on_triangle = foot, best.distance = std::abs(sp) / std::sqrt(nn);
      return best;
    }
  } else if (s0 != s1) {
    // Crossing the plane: inside the face there (with a rounding's margin), distance 0.
    const Vec3 x = p0 + (s0 / (s0 - s1)) * (p1 - p0);
    if (face.inside(x, 1e-12)) {
      best.on_segment = x, best.on_triangle = x, best.distance = 0;
      return best;
    }
  }
  Nearest nearest{best};
  face.offer_beyond_plane(p0, p1, p0 - (s0 / nn) * n, p1 - (s1 / nn) * n, nearest);
  best.distance = std::sqrt(nearest.d2);
  return best;
}

// A quad as segment_convex takes it.
struct QuadFace {
  const scene::Scene::Quad& q;
  // Inside the quad: on the inner side of each of its four outer edges (never of the diagonal
  // between its triangles, which a point within rounding of it could fail on both sides of),
  // within `eps` metres.
  bool inside(const Vec3& x, double eps) const {
    for (std::size_t i = 0; i < 4; ++i)
      if (!(q.inward[i].dot(x - q.corner[i]) >= -eps)) return false;
    return true;
  }
  // Each end's foot inside is a candidate; an edge is, only where a foot lies beyond it (or
  // within a nanometre of it): the nearest point of a convex face to a point beyond its rim
  // lies on an edge that point is beyond, and the side of an edge is linear along the segment
  // (as for a plate's polygon, PolygonDistance).
  void offer_beyond_plane(const Vec3& p0, const Vec3& p1, const Vec3& foot0, const Vec3& foot1, Nearest& nearest) const {
    std::array<bool, 4> beyond{};
    bool inside0 = true, inside1 = true;
    for (std::size_t i = 0; i < 4; ++i) {
      const double b0 = q.inward[i].dot(foot0 - q.corner[i]), b1 = q.inward[i].dot(foot1 - q.corner[i]);
      inside0 = inside0 && b0 >= 0, inside1 = inside1 && b1 >= 0;
      beyond[i] = !(b0 >= kEdgeSlack) || !(b1 >= kEdgeSlack);
    }
    if (inside0) nearest.offer(p0, foot0);
    if (inside1) nearest.offer(p1, foot1);
    const Vec3 d = p1 - p0;
    Vec3 cs, ct;
    for (std::size_t i = 0; i < 4; ++i)
      if (beyond[i]) nearest_segments(p0, d, q.corner[i], q.edge[i], cs, ct), nearest.offer(cs, ct);
  }
};

// The closest points of a segment and a plate fanned from an inner point (scene::Scene::Polygon).
// As a quad's, but with many corners: a point of the plane is placed in its wedge (between the
// rays from the centre to two neighbouring corners) by its angle, and only the edges that can
// hold the nearest point are measured. A point beyond the rim lies beyond the edge of its wedge,
// and a convex polygon's nearest point to it lies on an edge whose inner side it is beyond (or
// at a corner of two, one of them such), and those edges run on from its wedge's; the nearest
// point of the segment's, where it is not a foot inside, is nearest some point of the segment
// whose foot is beyond such an edge, and that edge is beyond a foot of one of its ends (the
// side of an edge is linear along the segment). So the feet of the two ends decide which edges.
class PolygonDistance {
 public:
  explicit PolygonDistance(const scene::Scene::Polygon& p) : p_(p) {}

  // The edge of the wedge x's foot lies in (its first corner's number).
  std::size_t wedge(const Vec3& x) const {
    const Vec3 r = x - p_.centre;
    const double a = std::atan2(r.dot(p_.v), r.dot(p_.u));
    const double* begin = p_.angle;
    const double* end = p_.angle + p_.count;
    const std::size_t k = static_cast<std::size_t>(std::upper_bound(begin, end, a) - begin);  // corners at or below a
    return (p_.first + (k == 0 ? p_.count - 1 : k - 1)) % p_.count;
  }
  // How far x is inside edge i (negative: beyond it).
  double inside_edge(const Vec3& x, std::size_t i) const { return p_.inward[i].dot(x - p_.corner[i]); }
  // Inside, within eps: inside its wedge's edge and the two beside it (an angle rounded across a
  // corner's ray places it in the next wedge; inside the true wedge's edge it is inside).
  bool inside(const Vec3& x, double eps) const { return inside_at(x, few() ? 0 : wedge(x), eps); }
  // The same with x's wedge w known (unused when the polygon has so few corners that every edge
  // is tested).
  bool inside_at(const Vec3& x, std::size_t w, double eps) const { return few() ? inside_all(x, eps) : inside_wedge(x, w, eps); }
  bool few() const { return p_.count <= kAllEdges; }
  bool inside_all(const Vec3& x, double eps) const {
    for (std::size_t i = 0; i < p_.count; ++i)
      if (!(inside_edge(x, i) >= -eps)) return false;
    return true;
  }
  bool inside_wedge(const Vec3& x, std::size_t w, double eps) const {
    return inside_edge(x, w) >= -eps && inside_edge(x, (w + 1) % p_.count) >= -eps && inside_edge(x, (w + p_.count - 1) % p_.count) >= -eps;
  }
  // Every edge the foot x lies beyond (or within kEdgeSlack of), added to `edges` once; false when
  // they do not fit (the caller then measures every edge).
  template <std::size_t N>
  bool edges_beyond(const Vec3& x, std::size_t w, std::array<std::size_t, N>& edges, std::size_t& n) const {
    const std::size_t K = p_.count;
    const auto beyond = [&](std::size_t i) { return !(inside_edge(x, i) >= kEdgeSlack); };
    const auto add = [&](std::size_t i) {
      for (std::size_t j = 0; j < n; ++j)
        if (edges[j] == i) return true;
      if (n == N) return false;
      edges[n++] = i;
      return true;
    };
    // From each of the wedge's edge and its two neighbours that x is beyond, on round the rim
    // both ways while it stays beyond.
    for (const std::size_t start : {(w + K - 1) % K, w, (w + 1) % K}) {
      if (!beyond(start)) continue;
      if (!add(start)) return false;
      for (std::size_t i = (start + 1) % K, steps = 0; steps < K && beyond(i); i = (i + 1) % K, ++steps)
        if (!add(i)) return false;
      for (std::size_t i = (start + K - 1) % K, steps = 0; steps < K && beyond(i); i = (i + K - 1) % K, ++steps)
        if (!add(i)) return false;
    }
    return true;
  }

  // The candidates beyond the plane's own (segment_convex): each end's foot inside, and the
  // edges beyond the two feet (every edge, where they are more than the list keeps, or the
  // polygon has so few). Each foot's wedge is found once.
  void offer_beyond_plane(const Vec3& p0, const Vec3& p1, const Vec3& foot0, const Vec3& foot1, Nearest& nearest) const {
    const std::size_t w0 = few() ? 0 : wedge(foot0), w1 = few() ? 0 : wedge(foot1);
    if (inside_at(foot0, w0, 0.0)) nearest.offer(p0, foot0);
    if (inside_at(foot1, w1, 0.0)) nearest.offer(p1, foot1);
    std::array<std::size_t, 32> edges;  // NOLINT: the first `count` are set
    std::size_t count = 0;
    const bool some = !few() && edges_beyond(foot0, w0, edges, count) && edges_beyond(foot1, w1, edges, count);
    if (some) std::sort(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(count));  // (in the rim's order, whichever end found them)
    const Vec3 d = p1 - p0;
    Vec3 cs, ct;
    const std::size_t measured = some ? count : p_.count;
    for (std::size_t j = 0; j < measured; ++j) {
      const std::size_t i = some ? edges[j] : j;
      nearest_segments(p0, d, p_.corner[i], p_.edge[i], cs, ct), nearest.offer(cs, ct);
    }
  }

  static constexpr std::size_t kAllEdges = 8;  // a polygon of so few corners has every edge measured

 private:
  const scene::Scene::Polygon& p_;
};

}  // namespace

SegmentTriangle segment_face(const Vec3& p0, const Vec3& p1, const scene::Scene& scene, std::uint32_t f) {
  if (const scene::Scene::Quad* q = scene.face_quad(f)) return segment_convex(p0, p1, q->normal, q->nn, q->corner[0], QuadFace{*q});
  if (const scene::Scene::Polygon* poly = scene.face_polygon(f))
    return segment_convex(p0, p1, poly->normal, poly->nn, poly->centre, PolygonDistance(*poly));
  return segment_triangle(p0, p1, scene.face_edges(f), scene.face_gram(f));
}

void StartDepths::add(std::uint32_t f, double depth, bool is_ground) {
  deepest = std::max(deepest, depth);
  if (is_ground) ground = std::max(ground, depth);
  for (int i = 0; i < count; ++i)
    if (faces[static_cast<std::size_t>(i)] == f) {
      depths[static_cast<std::size_t>(i)] = std::max(depths[static_cast<std::size_t>(i)], depth);
      return;
    }
  if (count == kMax) {
    overflow = true;
    return;
  }
  faces[static_cast<std::size_t>(count)] = f, depths[static_cast<std::size_t>(count)] = depth, ++count;
}

double StartDepths::of(std::uint32_t f, bool is_ground) const {
  if (overflow) return deepest;
  double d = is_ground ? ground : 0.0;
  for (int i = 0; i < count; ++i)
    if (faces[static_cast<std::size_t>(i)] == f) d = std::max(d, depths[static_cast<std::size_t>(i)]);
  return d;
}

bool FaceFilter::ignores(std::uint32_t f) const {
  if (ignored_guard < 0) return false;
  const auto& soup = scene->soup();
  return soup.labels[f] == scene::Surface::Guard && soup.guard_index[f] == static_cast<std::uint16_t>(ignored_guard);
}

double face_clearance(const scene::Scene& scene, std::uint32_t f, const projectile::Projectile& nail, const Vec3& centre, const Vec3& axis) {
  const double h = nail.half_segment();
  return segment_face(centre - h * axis, centre + h * axis, scene, f).distance - nail.radius();
}

void swept_box(const strike::Motion& m, const projectile::Projectile& nail, double from, double until, Vec3& lo, Vec3& hi) {
  const Vec3 a = m.centre(from), b = m.centre(until);
  lo = a.cwiseMin(b), hi = a.cwiseMax(b);
  // Each coordinate is a quadratic in time: its turning point, when inside the interval.
  const Vec3 v = m.velocity(from);
  for (int k = 0; k < 3; ++k) {
    if (m.a[k] == 0) continue;
    const double s = -v[k] / m.a[k];
    if (s > 0 && from + s < until) {
      const double x = m.centre(from + s)[k];
      lo[k] = std::min(lo[k], x), hi[k] = std::max(hi[k], x);
    }
  }
  const double reach = nail.half_segment() + nail.radius() + kFaceTolerance + 1e-9;
  lo.array() -= reach, hi.array() += reach;
}

namespace {

// One candidate face as the search sees it.
// (Left uninitialised in bulk: the search sets what it uses, for the faces it has.)
struct FaceState {
  std::uint32_t face;
  bool leaving;  // touched at a point moving away from it: no touch until that point moves in again
  double slack;  // a face being left: how far below the clearance it had then it may sink before it is looked at again
  double left_at;  // a face being left: its clearance then (a touch when its point turns back into it is placed there)
  double safe;   // a time before which the capsule surely does not reach it (a face being left: sink past the slack)
  SegmentTriangle exact;  // the closest points where it was last checked
  double exact_at;        // when (NaN: never in this search)
};

// Where the capsule is at one instant.
struct Pose {
  Vec3 centre, axis, velocity;
};


// The first x >= 0 at which f + df x - M x^2 / 2 reaches zero (f > 0, M > 0): a lower bound on
// when a clearance f with rate df and |f''| <= M can vanish.
double taylor_step(double f, double df, double M) {
  const double root = std::sqrt(df * df + 2 * M * f);
  const double denom = root - df;
  return denom > 0 ? 2 * f / denom : HUGE_VAL;
}

struct Search {
  const scene::Scene& scene;
  const strike::Motion& m;
  const projectile::Projectile& nail;
  const strike::Turning turning;
  const double h, r, w;
  Vec3 k = Vec3::Zero();  // the spin's unit axis (zero: no spin)
  double axis_along_k = 0, axis_across_k = 0;  // the nail's axis along k (fixed as it turns) and across it (its length, fixed)
  double bound = 0;  // how fast any point of the capsule can move

  Pose pose(double t) const { return {m.centre(t), turning.at(t - m.t0), m.velocity(t)}; }

  // The exact clearance of face f at pose p, with the closest points.
  double clearance(std::uint32_t f, const Pose& p, SegmentTriangle* st = nullptr) const {
    const SegmentTriangle s = segment_face(p.centre - h * p.axis, p.centre + h * p.axis, scene, f);
    if (st) *st = s;
    return s.distance - r;
  }

  // The contact's normal (from the face toward the core) and whether the capsule's touching
  // point moves into the face.
  bool approaching(std::uint32_t f, const Pose& p, const SegmentTriangle& s, Vec3& normal) const {
    const Vec3 gap = s.on_segment - s.on_triangle;
    const double len = gap.norm();
    if (len > 1e-12) {
      normal = gap / len;
    } else {  // the core on the face (never expected): the face's normal on the centre's side
      const Vec3& n = scene.face_normal(f);
      normal = n.dot(p.centre - s.on_triangle) >= 0 ? n : Vec3(-n);
    }
    const Vec3 arm = s.on_segment - r * normal - p.centre;
    return (p.velocity + m.spin.cross(arm)).dot(normal) < -kApproachSpeed;
  }

  // A time before which the capsule surely stays on the positive side of the plane through q
  // with unit normal n, less `slack` (0: it is not clear of it now). The plane separates it
  // from a face when the face lies on its far side (the face's own plane, or the plane through
  // the face's closest point across the line of the closest points), so this bounds the time
  // to reach the face. Each end's clearance f = n.(c - q) -+ h n.a - r + slack has
  // |f''| <= |n.acc| + h w^2: the first root of its second-order lower bound is safe; far from
  // the plane, the centre must first come within h + r of it (a quadratic, exact).
  double support_step(const Vec3& n, const Vec3& q, const Pose& p, double slack) const {
    const double s = n.dot(p.centre - q), along = n.dot(p.axis);
    if (!(s - h * std::abs(along) - r + slack > 0)) return 0.0;
    // The axis turns about k: n.a(t) = (n.k)(a.k) + n_perp . a_perp(t), with a_perp turning at
    // w in the plane across k, so |n.a| <= |n.k||a.k| + |n_perp||a_perp| (its reach) and
    // |(n.a)''| <= w^2 |n_perp||a_perp|. A nail spinning about the normal of a face (thrown
    // flat over the turf or under the plate) keeps its ends' height: no swing to bound.
    const double nk = n.dot(k), n_across = std::sqrt(std::max(0.0, 1 - nk * nk));
    const double reach = w > 0 ? std::min(1.0, std::abs(nk) * axis_along_k + n_across * axis_across_k) : std::abs(along);
    const double dc = n.dot(p.velocity), da = n.dot(m.spin.cross(p.axis));
    const double M = std::abs(n.dot(m.a)) + h * w * w * n_across * axis_across_k + 1e-12;
    const double base = s - r + slack, swing = h * along;
    double step = std::min(taylor_step(base - swing, dc - h * da, M), taylor_step(base + swing, dc + h * da, M));
    const double above = s - h * reach - r + slack;
    if (above > 0) step = std::max(step, first_root(above, dc, n.dot(m.a)));
    return step;
  }

  // A time the capsule surely cannot touch face f before (slack: how far into it it may go).
  // `best`: the least such time of the faces before; nothing exact is computed when a cheap
  // bound already shows this face is farther. `st`: the exact closest points now, when the
  // caller has them (`have` true; else they are worked out into it when needed, and `have`
  // set); `try_ball`: whether the face's ball is tried first.
  double safe_time(std::uint32_t f, const Pose& p, double slack, double best, bool try_ball, SegmentTriangle& st, bool& have) const {
    const Vec3& fn = scene.face_normal(f);
    const Vec3& q = scene.face_edges(f)[0];
    const Vec3 n = fn.dot(p.centre - q) >= 0 ? fn : Vec3(-fn);
    double safe = support_step(n, q, p, slack);
    if (safe >= best) return safe;
    if (try_ball) {
      // The face's ball: a cheap lower bound on the distance, from the core segment to its centre.
      const scene::Scene::Ball& ball = scene.face_ball(f);
      const Vec3 to = ball.centre - p.centre;
      const double along_axis = std::clamp(to.dot(p.axis), -h, h);
      const double ball_gap = (to - along_axis * p.axis).norm() - ball.radius - r + slack;
      if (ball_gap > 0 && std::max(safe, ball_gap / bound) >= best) return std::max(safe, ball_gap / bound);
    }
    if (!have) clearance(f, p, &st), have = true;
    const double g = st.distance - r + slack;
    if (!(g > 0)) return safe;
    // Across the line of the closest points, through the face's closest point.
    const Vec3 gap = st.on_segment - st.on_triangle;
    const double len = gap.norm();
    if (len > 0) safe = std::max(safe, support_step(gap / len, st.on_triangle, p, slack));
    return std::max(safe, g / bound);
  }
};

}  // namespace

std::optional<FaceTouch> first_face_touch(const scene::Scene& scene, const std::uint32_t* faces, std::size_t count,
                                          const strike::Motion& m, const projectile::Projectile& nail, double from, double until,
                                          const FaceFilter& filter, FaceSearchStats& stats) {
  constexpr std::size_t kCapacity = 256;
  std::array<FaceState, kCapacity> state;  // NOLINT: filled below for the first n
  std::size_t n = 0;
  for (std::size_t i = 0; i < count && n < kCapacity; ++i)
    if (!filter.ignores(faces[i])) state[n].face = faces[i], state[n].leaving = false, state[n].slack = 0, state[n].left_at = 0, state[n].safe = 0, state[n].exact_at = kNever, ++n;
  if (n == 0 || !(until >= from)) return std::nullopt;
  const double w = m.spin.norm();
  Search s{scene, m, nail, m.turning(), nail.half_segment(), nail.radius(), w};
  if (w > 0) {
    s.k = m.spin / w;
    s.axis_along_k = std::abs(m.axis0.dot(s.k));
    s.axis_across_k = std::sqrt(std::max(0.0, 1 - s.axis_along_k * s.axis_along_k));
  }
  s.bound = std::max(m.velocity(from).norm(), m.velocity(until).norm()) + s.h * w + 1e-9;

  // The faces within tolerance of the capsule at one instant, with their closest points, and
  // whether the closest point lies under the capsule (along the face's own normal: the
  // capsule on the face's inside, not at an edge or corner).
  struct Near {
    std::size_t i;
    SegmentTriangle st;
    double g;
    bool under;
  };
  std::array<Near, kCapacity> near;  // NOLINT: filled as it is used
  std::size_t near_count = 0;

  // A face being left that the capsule is deeper in than kDeepestSink (below the depth a field's
  // object started at in it): the search gives up on it (the caller cuts the nail off). Not the board, whose
  // touch ends the flight when it is approached: a nail laid flat on the turf at its foot can lie
  // a fraction of a millimetre into it, slide on and reach it, as it always did.
  const auto sink_check = [&](const FaceState& fs) {
    if (!(fs.left_at < -kDeepestSink)) return;
    const scene::Surface label = scene.soup().labels[fs.face];
    if (scene::is_target(label)) return;
    const double started = filter.start_depths ? filter.start_depths->of(fs.face, label == scene::Surface::Ground) : 0.0;
    if (fs.left_at < -(kDeepestSink + started)) stats.sank = true;
  };

  // Whether the capsule meets near face e at an edge or corner (`normal`, from that point
  // toward the core, off the face's own normal) inside one flat surface built of several faces
  // (a fan of triangles, a mesh, pieces of a skirt): another face near the capsule, of the
  // same material (label and guard), in the same plane at the touching point, has its closest
  // point under the capsule. Such an edge is not an edge of the steel: a round body resting on
  // a plane meets it along one line, and reaches a coplanar face's edge only when it has sunk
  // into the surface (by a face being left's slack); it moves along the surface, which the
  // face under it stands for. (Met as edges, a nail or stone sliding over them was thrown off
  // at the edge's tilted normal.)
  const auto flat_edge = [&](const Near& e, const Vec3& normal) {
    const std::uint32_t f = state[e.i].face;
    const Vec3& fn = scene.face_normal(f);
    if (std::abs(normal.dot(fn)) > 1 - 1e-9) return false;  // on the face's inside: its own plane
    const auto& soup = scene.soup();
    for (std::size_t k = 0; k < near_count; ++k) {
      const Near& u = near[k];
      if (&u == &e || !u.under) continue;
      const std::uint32_t g = state[u.i].face;
      const Vec3& gn = scene.face_normal(g);
      if (soup.labels[g] != soup.labels[f] || soup.guard_index[g] != soup.guard_index[f]) continue;
      if (std::abs(gn.dot(fn)) > 1 - 1e-10 && std::abs(gn.dot(e.st.on_triangle - u.st.on_triangle)) <= 1e-7) return true;
    }
    return false;
  };

  // What touches at time t among the faces within reach (those whose safe time the last step
  // did not clear): the lowest approaching face, with the count of distinct touching planes;
  // the others within tolerance are marked leaving, the rest not.
  const auto settle = [&](double t, const Pose& p, std::optional<FaceTouch>& touch) {
    std::array<Vec3, 4> normals;
    int distinct = 0;
    near_count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      FaceState& fs = state[i];
      // Clear of the face's plane (or of its ball), so of the face: nothing to settle.
      const Vec3& fn = scene.face_normal(fs.face);
      const double plane = std::abs(fn.dot(p.centre - scene.face_edges(fs.face)[0])) - s.h * std::abs(fn.dot(p.axis)) - s.r;
      const scene::Scene::Ball& ball = scene.face_ball(fs.face);
      // (With a margin: the exact test below decides at the tolerance itself, where the
      // search's roots lie, and the two must not disagree by a rounding.)
      constexpr double kMargin = 1e-9;
      if (plane > kFaceTolerance + kMargin || (ball.centre - p.centre).norm() - ball.radius - s.h - s.r > kFaceTolerance + kMargin) {
        fs.leaving = false;
        continue;
      }
      Near& e = near[near_count];
      e.i = i;
      e.g = s.clearance(fs.face, p, &e.st);
      fs.exact = e.st, fs.exact_at = t;  // (the bounds from here use them)
      if (e.g > kFaceTolerance) {
        fs.leaving = false;
        continue;
      }
      const Vec3 gap = e.st.on_segment - e.st.on_triangle;
      const double len = gap.norm();
      e.under = len > 1e-12 && std::abs(gap.dot(fn)) > (1 - 1e-9) * len;
      ++near_count;
    }
    for (std::size_t at = 0; at < near_count; ++at) {
      const Near& here = near[at];
      FaceState& fs = state[here.i];
      const SegmentTriangle& st = here.st;
      const double g = here.g;
      Vec3 normal;
      if (!s.approaching(fs.face, p, st, normal) || flat_edge(here, normal)) {
        // Left: it may sink kLeavingSlack into the face before it is looked at again. A
        // capsule that starts deep inside a face (a field's stone pressed into the soil, far
        // beyond what a touch of this search leaves) may sink no deeper than it is by the slack.
        if (!fs.leaving) fs.slack = g < -kEmbedded ? kLeavingSlack - g : kLeavingSlack, fs.left_at = g;
        fs.leaving = true;
        sink_check(fs);
        continue;
      }
      bool seen = false;
      for (int k = 0; k < distinct; ++k) seen = seen || normals[static_cast<std::size_t>(k)].dot(normal) > 1 - 1e-9;
      if (!seen && distinct < 4) normals[static_cast<std::size_t>(distinct++)] = normal;
      if (!touch || fs.face < touch->face) {
        const FaceTouch kept = touch ? *touch : FaceTouch{};
        touch = FaceTouch{};
        touch->time = t, touch->centre = p.centre, touch->axis = p.axis, touch->point = st.on_triangle, touch->normal = normal;
        touch->face = fs.face;
        touch->points = kept.points, touch->point_count = kept.point_count;
      }
      // The touching points: this face's closest one, and the core's ends within tolerance of
      // it apart from that one (a nearly flat rod's other end), each moving into it.
      const auto add = [&](const Vec3& on_face, const Vec3& dir, const Vec3& on_core) {
        if (touch->point_count >= FaceTouch::kMaxTouchPoints) return;
        const Vec3 arm = on_core - s.r * dir - p.centre;
        for (int k = 0; k < touch->point_count; ++k)
          if ((touch->points[static_cast<std::size_t>(k)].arm - arm).norm() < s.r && touch->points[static_cast<std::size_t>(k)].normal.dot(dir) > 1 - 1e-9) return;
        touch->points[static_cast<std::size_t>(touch->point_count++)] = TouchPoint{on_face, dir, arm, fs.face};
      };
      add(st.on_triangle, normal, st.on_segment);
      for (const double end : {-s.h, s.h}) {
        const Vec3 tip = p.centre + end * p.axis;
        if ((tip - st.on_segment).norm() < s.r) continue;  // the closest point already
        const SegmentTriangle e = segment_face(tip, tip, scene, fs.face);
        if (e.distance - s.r > kFaceTolerance) continue;
        const Vec3 gap = e.on_segment - e.on_triangle;
        const Vec3 dir = gap.norm() > 1e-12 ? Vec3(gap.normalized()) : normal;
        if ((p.velocity + m.spin.cross(tip - s.r * dir - p.centre)).dot(dir) < -kApproachSpeed) add(e.on_triangle, dir, tip);
      }
    }
    if (touch) {
      touch->touching = std::max(1, distinct);
      // The touch's own point first.
      for (int k = 1; k < touch->point_count; ++k)
        if (touch->points[static_cast<std::size_t>(k)].face == touch->face && touch->points[static_cast<std::size_t>(k)].point == touch->point) {
          std::swap(touch->points[0], touch->points[static_cast<std::size_t>(k)]);
          break;
        }
    }
  };

  double t = from;
  std::optional<FaceTouch> touch;
  Pose at_t = s.pose(t);
  settle(t, at_t, touch);
  if (stats.sank) return std::nullopt;
  if (touch) return touch;
  const double min_step = kMinFaceStep / s.bound;
  // Each face's safe time is a bound over the whole motion, so it holds until that time: a
  // face is looked at again only when the search reaches it (most faces of a chord once).
  // (The face's closest points at `at`, fs.exact, are used where it holds them; `ball`: its
  // ball is tried first.)
  const auto bound_from = [&](FaceState& fs, const Pose& p, double at, double best, bool ball) {
    bool have = fs.exact_at == at;
    const auto safe_time = [&](double slack) {
      const double safe = s.safe_time(fs.face, p, slack, best, ball, fs.exact, have);
      if (have) fs.exact_at = at;
      return safe;
    };
    double safe = safe_time(fs.leaving ? fs.slack : 0.0);
    // A face being left that the capsule has entered by the slack without moving into it
    // (its touching point turning about the contact as it slides over the face): the slack
    // counts again from where it is (a nail or stone is never pushed out of a face by this;
    // past kDeepestSink, sink_check gives up). So it does where
    // what is left of the slack lets the capsule move less than kSlackSpent: with a nanometre
    // left, the bound is a few nanoseconds, not zero, and the search would step by them, each
    // step ending in a touch of a contact with no rebound (a flap at e = 0 pressed by a nail
    // sliding on under it: 100 000 gentle contacts, 2 ns apart, and the nail cut off).
    if (fs.leaving && !(safe * s.bound > kSlackSpent)) {
      if (!have) s.clearance(fs.face, p, &fs.exact), have = true, fs.exact_at = at;
      fs.left_at = fs.exact.distance - s.r;
      fs.slack = kLeavingSlack - std::min(0.0, fs.left_at);
      sink_check(fs);
      safe = safe_time(fs.slack);
      if (!(safe > 0)) safe = kLeavingSlack / s.bound;
    }
    // Not reached before the chord's end: this search need not look at it again (so nothing
    // exact is worked out for a face whose plane alone keeps it clear of the whole chord).
    fs.safe = safe >= until - at ? HUGE_VAL : at + safe;
  };
  const auto bound_all = [&](const Pose& p, double at) {
    double best = until - at;
    for (std::size_t i = 0; i < n; ++i) {
      bound_from(state[i], p, at, best, true);
      if (!state[i].leaving) best = std::min(best, state[i].safe - at);
    }
  };
  bound_all(at_t, t);
  while (t < until) {
    if (stats.sank) return std::nullopt;
    if (++stats.steps > kMaxFaceSearchSteps) {
      stats.gave_up = true;
      return std::nullopt;
    }
    // The step: to the earliest safe time of the faces approached (but at least min_step of
    // motion), and of the faces being left (which may sink kLeavingSlack into their face first).
    double reach_new = HUGE_VAL, reach_leaving = HUGE_VAL;
    for (std::size_t i = 0; i < n; ++i) (state[i].leaving ? reach_leaving : reach_new) = std::min(state[i].leaving ? reach_leaving : reach_new, state[i].safe);
    const double next = std::min(until, std::max(std::min(std::max(reach_new, t + min_step), reach_leaving), next_up(t)));
    // The faces the step may have reached, checked at its end: a face approached and now
    // within tolerance is brought back to its first touch; a face being left that is now
    // moving into it is touched there.
    const Pose q = s.pose(next);
    double first = HUGE_VAL;
    for (std::size_t i = 0; i < n; ++i) {
      FaceState& fs = state[i];
      if (fs.safe > next) continue;  // surely not reached within the step
      SegmentTriangle& st = fs.exact;
      // (Its clearance at the step's start, when known there: the root's bracket.)
      const double distance_at_t = fs.exact_at == t ? fs.exact.distance : HUGE_VAL;
      const double g_next = s.clearance(fs.face, q, &st);
      fs.exact_at = next;
      if (g_next > kFaceTolerance) continue;
      if (fs.leaving) {
        Vec3 normal;
        if (!s.approaching(fs.face, q, st, normal)) continue;
        // Its touching point turned back into it within the step: touched there. An object
        // that was left deep in the face (a field's stone pressed into the soil) is touched
        // where it came back to within the tolerance below the depth it left the face at, not
        // after sinking the slack: struck and falling back again and again, it would sink by the
        // slack each time (an audit found a cobble 0.14 mm deeper after 14 strikes).
        const double target = fs.left_at - kFaceTolerance;
        const double g_hi = g_next - target, g_lo = fs.left_at < -kEmbedded && g_hi <= 0 ? s.clearance(fs.face, at_t) - target : 0.0;
        first = std::min(first, g_lo > 0 ? illinois_root(
                                               t, g_lo, next, g_hi, [&](double t_mid) { return s.clearance(fs.face, s.pose(t_mid)) - target; },
                                               s.bound, kFaceTolerance, 80, [](double, double) { return false; })
                                         : next);
        continue;
      }
      // Regula falsi (Illinois) on clearance - tolerance, from t (clear: the face was surely
      // not reached before its safe time) to next.
      double lo = t, hi = next, g_hi = g_next - kFaceTolerance;
      double g_lo = (distance_at_t != HUGE_VAL ? distance_at_t - s.r : s.clearance(fs.face, at_t)) - kFaceTolerance;
      if (g_lo <= 0) {  // within tolerance at t already (a face the step's start grazed): there
        first = std::min(first, t);
        continue;
      }
      hi = illinois_root(
          lo, g_lo, hi, g_hi, [&](double t_mid) { return s.clearance(fs.face, s.pose(t_mid)) - kFaceTolerance; }, s.bound, kFaceTolerance, 80,
          [](double, double) { return false; });
      first = std::min(first, hi);
    }
    if (first == HUGE_VAL) {
      // Clear: the faces reached are bounded again from here.
      double best = until - next;
      for (std::size_t i = 0; i < n; ++i)
        if (state[i].safe <= next) {
          bound_from(state[i], q, next, best, false);  // (its closest points at `next` known: the step worked them out)
          if (!state[i].leaving) best = std::min(best, state[i].safe - next);
        }
      t = next;
      at_t = q;
      continue;
    }
    // Something is within tolerance at `first`: a touch if a point there moves into a face;
    // else the capsule grazes on (those faces are now being left), every face bounded anew.
    // (From `first` itself, even when that is where the step began: the faces found there are
    // now bounded as faces being left, which the next step respects.)
    at_t = s.pose(first);
    settle(first, at_t, touch);
    if (stats.sank) return std::nullopt;
    if (touch) return touch;
    t = first;
    bound_all(at_t, t);
  }
  return std::nullopt;
}

}  // namespace j232::flight
