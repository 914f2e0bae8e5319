// The capsule's contact search against the scene's real faces (flight/face_touch.hpp),
// checked against code it does not share: CGAL's distances (scene/capsule_audit.hpp) and a
// fine fixed-step scan of the motion.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "flight/face_touch.hpp"
#include "flight/flight_audit.hpp"
#include "scene/capsule_audit.hpp"
#include "scene/scene.hpp"

using namespace j232;
using Vec3 = Eigen::Vector3d;

namespace {
double uniform(std::mt19937_64& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
Vec3 random_vec(std::mt19937_64& rng, double scale) { return Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)) * scale; }

// A small scene of random triangles near the origin, every engine built in.
scene::Soup random_soup(std::mt19937_64& rng, int triangles) {
  scene::Soup soup;
  for (int t = 0; t < triangles; ++t) {
    const Vec3 c = random_vec(rng, 0.05);
    const auto a = soup.add_point(c + random_vec(rng, 0.04)), b = soup.add_point(c + random_vec(rng, 0.04)),
               d = soup.add_point(c + random_vec(rng, 0.04));
    soup.add_triangle(a, b, d, scene::Surface::Housing);
  }
  return soup;
}

// A flat convex quad near the origin (corners on an ellipse in a random plane, in order
// round it), added as Soup::add_quad adds a panel: two triangles the scene takes as one face.
void add_random_quad(std::mt19937_64& rng, scene::Soup& soup, scene::Surface label = scene::Surface::Housing) {
  const Vec3 c = random_vec(rng, 0.05), u = random_vec(rng, 1).normalized();
  const Vec3 v = u.cross(random_vec(rng, 1)).normalized();
  const double ra = uniform(rng, 0.005, 0.06), rb = uniform(rng, 0.005, 0.06);
  std::array<double, 4> angle{};
  for (double& a : angle) a = uniform(rng, 0, 2 * M_PI);
  std::sort(angle.begin(), angle.end());
  std::array<std::uint32_t, 4> id{};
  for (std::size_t k = 0; k < 4; ++k) id[k] = soup.add_point(c + ra * std::cos(angle[k]) * u + rb * std::sin(angle[k]) * v);
  soup.add_quad(id[0], id[1], id[2], id[3], label);
}

// The pose of a motion by independent formulas (the audit's).
void pose(const strike::Motion& m, double t, Vec3& centre, Vec3& axis) {
  const double dt = t - m.t0, w = m.spin.norm();
  centre = m.p0 + m.v0 * dt + 0.5 * dt * dt * m.a;
  axis = w > 0 ? Vec3(Eigen::AngleAxisd(w * dt, m.spin / w) * m.axis0) : m.axis0;
}
}  // namespace

TEST_CASE("face touch: the segment-triangle distance is CGAL's", "[flight][contact]") {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 20000; ++trial) {
    scene::Soup soup = random_soup(rng, 1);
    const std::array<Vec3, 3> tri{soup.points[0], soup.points[1] - soup.points[0], soup.points[2] - soup.points[0]};
    const Vec3 c = random_vec(rng, 0.1), axis = random_vec(rng, 1).normalized();
    // Some segments lie in or across the triangle's plane, some are points (a sphere's core).
    const double h = trial % 7 == 0 ? 0.0 : uniform(rng, 0.001, 0.05);
    const Vec3 centre = trial % 5 == 0 ? Vec3(soup.points[0] + 0.3 * tri[1] + 0.3 * tri[2]) : c;
    const auto ours = flight::segment_triangle(centre - h * axis, centre + h * axis, tri);
    const auto cgal = scene::deepest_overlap(soup, centre, axis, h, 1.0);  // a radius that reaches it: the depth is 1 - distance
    CHECK(ours.distance == Approx(1.0 - cgal.depth).margin(1e-12));
    CHECK((ours.on_segment - ours.on_triangle).norm() == Approx(ours.distance).margin(1e-12));
  }
}

// A segment's centre and axis about `anchor` on a face's plane of unit normal `normal`: kind 2
// parallel to the plane, over it or beside it; kind 3 in the plane.
void pose_by_plane(std::mt19937_64& rng, int kind, const Vec3& anchor, const Vec3& normal, Vec3& centre, Vec3& axis) {
  if (kind == 2) {
    centre = anchor + random_vec(rng, 0.03) + uniform(rng, -0.01, 0.01) * normal, axis = (axis - axis.dot(normal) * normal).normalized();
    centre -= normal.dot(centre - anchor) * normal - uniform(rng, -0.01, 0.01) * normal;
  } else {
    centre = anchor + random_vec(rng, 0.05), centre -= normal.dot(centre - anchor) * normal;
    axis = (axis - axis.dot(normal) * normal).normalized();
  }
}

// A segment in a face's plane: CGAL 5.5's segment-triangle distance takes it as crossing the
// plane (rounding) and calls it 0 where it passes beside the face. The reference is then CGAL's
// distance from points along it (exact for points), at least the true distance and at most a
// step beyond it: `ours` is checked within that.
void check_in_plane(const scene::Soup& soup, const Vec3& p0, const Vec3& p1, const Vec3& axis, double h, double ours) {
  double sampled = HUGE_VAL;
  constexpr int kSamples = 400;
  for (int k = 0; k <= kSamples; ++k)
    sampled = std::min(sampled, 1.0 - scene::deepest_overlap(soup, p0 + (k / double(kSamples)) * (p1 - p0), axis, 0.0, 1.0).depth);
  CHECK(ours <= sampled + 1e-12);
  CHECK(ours >= sampled - 2 * h / kSamples - 1e-12);
}

// A flat convex polygon of `corners` corners near the origin (on an ellipse in a random plane,
// in order round it), fanned from an inner point (a random mean of its corners) as a deck's
// plate is: triangles (c, p_k, p_k+1) round to p_0, their points shared or each its own.
std::vector<Vec3> add_random_polygon(std::mt19937_64& rng, scene::Soup& soup, std::size_t corners, bool shared_points) {
  const Vec3 c = random_vec(rng, 0.05), u = random_vec(rng, 1).normalized();
  const Vec3 v = u.cross(random_vec(rng, 1)).normalized();
  const double ra = uniform(rng, 0.01, 0.08), rb = uniform(rng, 0.01, 0.08);
  std::vector<double> angle(corners);
  for (double& a : angle) a = uniform(rng, 0, 2 * M_PI);
  std::sort(angle.begin(), angle.end());
  std::vector<Vec3> rim;
  for (const double a : angle) rim.push_back(c + ra * std::cos(a) * u + rb * std::sin(a) * v);
  Vec3 inner = Vec3::Zero();
  double weights = 0;
  for (const Vec3& p : rim) {
    const double w = uniform(rng, 0.1, 1);
    inner += w * p, weights += w;
  }
  inner /= weights;
  const auto centre = soup.add_point(inner);
  std::vector<std::uint32_t> id;
  for (const Vec3& p : rim) id.push_back(soup.add_point(p));
  for (std::size_t k = 0; k < corners; ++k) {
    const std::size_t next = (k + 1) % corners;
    if (shared_points) soup.add_triangle(centre, id[k], id[next], scene::Surface::Housing);
    else soup.add_triangle(soup.add_point(inner), soup.add_point(rim[k]), soup.add_point(rim[next]), scene::Surface::Housing);
  }
  return rim;
}

TEST_CASE("face touch: a plate fanned from an inner point is one face, and its distance is CGAL's to its triangles", "[flight][contact]") {
  std::mt19937_64 rng(61);
  int merged = 0, trials = 0;
  for (int trial = 0; trial < 6000; ++trial, ++trials) {
    scene::Soup soup;
    const std::size_t corners = trial % 3 == 0 ? 3 + static_cast<std::size_t>(trial / 3 % 7) : 9 + static_cast<std::size_t>(trial % 140);
    const std::vector<Vec3> rim = add_random_polygon(rng, soup, corners, trial % 2 == 0);
    const scene::Scene scene(soup, scene::Engine::Cgal);
    // (Corners drawn very close together can make a sliver whose corner turns back by more than
    // rounding: then triangles, each its own face, which the distance below checks the same.)
    const bool one = scene.face_polygon(0) != nullptr;
    merged += one;
    std::array<std::uint32_t, 256> listed{};
    const std::size_t n = scene.faces_in_box(Vec3::Constant(-1), Vec3::Constant(1), listed.data(), listed.size());
    if (one) {
      CHECK(n == 1);
      CHECK(scene.face_polygon(0)->count == corners);
      for (std::uint32_t f = 1; f < corners; ++f) CHECK(scene.face_polygon(f) == nullptr);
    }
    const Vec3 normal = (soup.points[1] - soup.points[0]).cross(soup.points[2] - soup.points[0]).normalized();
    const Vec3& corner = rim[static_cast<std::size_t>(trial) % corners];
    const Vec3 by_rim = corner + uniform(rng, 0, 1) * (rim[(static_cast<std::size_t>(trial) + 1) % corners] - corner);
    Vec3 centre = random_vec(rng, 0.1), axis = random_vec(rng, 1).normalized();
    const double h = trial % 7 == 0 ? 0.0 : uniform(rng, 0.001, 0.05);
    // Where the polygon's angles wrap (the direction from its centre opposite its first corner).
    const Vec3 inner = soup.points[soup.triangles[0][0]], seam = inner - 0.5 * (rim[0] - inner);
    switch (trial % 6) {
      case 1:  // by the rim, tilted across the plane; a third of them with an end's foot on the rim exactly, or about the seam
        centre = by_rim + random_vec(rng, 0.01), axis = (axis - axis.dot(normal) * normal + 0.3 * normal).normalized();
        if (trial % 18 == 1) centre = by_rim + uniform(rng, 0.001, 0.02) * normal + h * axis;
        if (trial % 18 == 7) centre = seam + random_vec(rng, 0.02);
        break;
      case 2:  // parallel to the plane, over it or beside it
      case 3:  // in the plane
        pose_by_plane(rng, trial % 6, by_rim, normal, centre, axis);
        break;
      case 4:  // by a corner
        centre = corner + random_vec(rng, 1e-3);
        break;
      default:
        break;
    }
    const Vec3 p0 = centre - h * axis, p1 = centre + h * axis;
    double ours = HUGE_VAL;
    for (std::uint32_t f = 0; f < (one ? 1u : static_cast<std::uint32_t>(corners)); ++f) ours = std::min(ours, flight::segment_face(p0, p1, scene, f).distance);
    INFO("trial " << trial << ", case " << trial % 6 << ", corners " << corners);
    if (trial % 6 != 3) {
      // (epsilon(0): Catch's Approx keeps a relative 1e-5 beside a margin unless told.)
      CHECK(ours == Approx(1.0 - scene::deepest_overlap(soup, centre, axis, h, 1.0).depth).epsilon(0).margin(1e-12));
    } else {
      check_in_plane(soup, p0, p1, axis, h, ours);
    }
    if (one) {  // the closest points: on the segment, on the polygon, that far apart
      const auto st = flight::segment_face(p0, p1, scene, 0);
      CHECK((st.on_segment - st.on_triangle).norm() == Approx(st.distance).margin(1e-12));
      CHECK(1.0 - scene::deepest_overlap(soup, st.on_triangle, axis, 0.0, 1.0).depth <= 1e-12);
      const double along = h > 0 ? std::clamp((st.on_segment - p0).dot(p1 - p0) / (p1 - p0).squaredNorm(), 0.0, 1.0) : 0.0;
      CHECK((p0 + along * (p1 - p0) - st.on_segment).norm() <= 1e-12);
    }
  }
  CHECK(merged > 0.95 * trials);
  // Not one face: a fan that does not close, one of two labels, or a rim that turns back.
  const auto one_face = [](const std::vector<Vec3>& rim, bool close, scene::Surface last_label) {
    scene::Soup soup;
    const auto c = soup.add_point(Vec3::Zero());
    std::vector<std::uint32_t> id;
    for (const Vec3& p : rim) id.push_back(soup.add_point(p));
    const std::size_t count = close ? rim.size() : rim.size() - 1;
    for (std::size_t k = 0; k < count; ++k)
      soup.add_triangle(c, id[k], id[(k + 1) % rim.size()], k + 1 == count ? last_label : scene::Surface::Housing);
    return scene::Scene(soup, scene::Engine::Cgal).face_polygon(0) != nullptr;
  };
  std::vector<Vec3> hexagon;
  for (int k = 0; k < 6; ++k) hexagon.emplace_back(0.1 * std::cos(k * M_PI / 3), 0.1 * std::sin(k * M_PI / 3), 0);
  CHECK(one_face(hexagon, true, scene::Surface::Housing));
  CHECK_FALSE(one_face(hexagon, false, scene::Surface::Housing));
  CHECK_FALSE(one_face(hexagon, true, scene::Surface::Ground));
  std::vector<Vec3> dented = hexagon;
  dented[2] *= 0.3;  // a corner pushed in: a star, not convex
  CHECK_FALSE(one_face(dented, true, scene::Surface::Housing));
}

TEST_CASE("face touch: a flat convex quad is one face, and its distance is CGAL's to its two triangles", "[flight][contact]") {
  std::mt19937_64 rng(6);
  int quads = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    scene::Soup soup;
    add_random_quad(rng, soup);
    const scene::Scene scene(soup, scene::Engine::Cgal);
    // (Four corners on an ellipse may make a sliver the scene refuses to merge: then two
    // triangles, each its own face, which the distance below checks just the same.)
    quads += scene.face_quad(0) != nullptr;
    Vec3 centre = random_vec(rng, 0.1), axis = random_vec(rng, 1).normalized();
    const double h = trial % 7 == 0 ? 0.0 : uniform(rng, 0.001, 0.05);
    const Vec3 normal = (soup.points[1] - soup.points[0]).cross(soup.points[2] - soup.points[0]).normalized();
    const Vec3 on_diagonal = soup.points[0] + uniform(rng, 0, 1) * (soup.points[2] - soup.points[0]);
    switch (trial % 6) {
      case 1:  // an end's foot on the diagonal between the two triangles, exactly as rounding puts it
        centre = on_diagonal + uniform(rng, -0.02, 0.02) * normal, axis = (axis - axis.dot(normal) * normal + 0.3 * normal).normalized();
        centre += h * axis;
        break;
      case 2:  // parallel to the plane, over it or beside it
      case 3:  // in the plane
        pose_by_plane(rng, trial % 6, on_diagonal, normal, centre, axis);
        break;
      case 4:  // by a corner
        centre = soup.points[static_cast<std::size_t>(trial % 4)] + random_vec(rng, 1e-3);
        break;
      default:
        break;
    }
    const Vec3 p0 = centre - h * axis, p1 = centre + h * axis;
    double ours = flight::segment_face(p0, p1, scene, 0).distance;
    if (!scene.face_quad(0)) ours = std::min(ours, flight::segment_face(p0, p1, scene, 1).distance);
    const auto cgal = scene::deepest_overlap(soup, centre, axis, h, 1.0);
    INFO("trial " << trial << ", case " << trial % 6);
    if (trial % 6 != 3) {
      CHECK(ours == Approx(1.0 - cgal.depth).epsilon(0).margin(1e-12));
    } else {
      check_in_plane(soup, p0, p1, axis, h, ours);
    }
    // The closest points: on the segment, on the quad (CGAL's distance to it nil), that far apart.
    const auto st = flight::segment_face(p0, p1, scene, 0);
    CHECK((st.on_segment - st.on_triangle).norm() == Approx(st.distance).margin(1e-12));
    if (scene.face_quad(0)) {
      CHECK(1.0 - scene::deepest_overlap(soup, st.on_triangle, axis, 0.0, 1.0).depth <= 1e-12);
      const double along = h > 0 ? std::clamp((st.on_segment - p0).dot(p1 - p0) / (p1 - p0).squaredNorm(), 0.0, 1.0) : 0.0;
      CHECK((p0 + along * (p1 - p0) - st.on_segment).norm() <= 1e-12);
    }
  }
  CHECK(quads > 19000);
  // Not one face: two triangles that do not make a flat convex quad with one label.
  const auto merged = [](const std::array<Vec3, 4>& corner, scene::Surface second_label) {
    scene::Soup soup;
    std::array<std::uint32_t, 4> id{};
    for (std::size_t k = 0; k < 4; ++k) id[k] = soup.add_point(corner[k]);
    soup.add_triangle(id[0], id[1], id[2], scene::Surface::Housing);
    soup.add_triangle(id[0], id[2], id[3], second_label);
    const scene::Scene scene(soup, scene::Engine::Cgal);
    std::array<std::uint32_t, 4> listed{};
    const std::size_t n = scene.faces_in_box(Vec3::Constant(-1), Vec3::Constant(1), listed.data(), listed.size());
    CHECK(n == (scene.face_quad(0) ? 1u : 2u));
    CHECK(scene.face_quad(1) == nullptr);
    return scene.face_quad(0) != nullptr;
  };
  const std::array<Vec3, 4> square{Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.1, 0.1, 0), Vec3(0, 0.1, 0)};
  CHECK(merged(square, scene::Surface::Housing));
  CHECK_FALSE(merged(square, scene::Surface::Ground));                                                                  // two labels
  CHECK_FALSE(merged({Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.1, 0.1, 0), Vec3(0, 0.1, 1e-4)}, scene::Surface::Housing));  // folded
  CHECK_FALSE(merged({Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.02, 0.02, 0), Vec3(0, 0.1, 0)}, scene::Surface::Housing));   // a dart
}

TEST_CASE("face touch: the first touch of a tumbling capsule is a fine scan's, and it never passes through a face", "[flight][contact]") {
  std::mt19937_64 rng(11);
  // A 6d nail, and the smallest field object allowed (1 mm grit, a sphere: the capsule of no
  // length), which thin faces must stop as well.
  const bool grit = GENERATE(false, true);
  const auto nail = grit ? projectile::Projectile::sphere(0.001, 1.4e-6) : projectile::Projectile::capsule(0.0508, 0.00287, 0.0021);
  int touches = 0, misses = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // Half the scenes are of quads (two triangles each, one face to the search).
    scene::Soup soup = trial % 2 ? scene::Soup{} : random_soup(rng, 6);
    if (trial % 2)
      for (int k = 0; k < 4; ++k) add_random_quad(rng, soup);
    const scene::Scene scene(soup, trial % 2 ? scene::Engine::Cgal : scene::default_engine());
    strike::Motion m;
    m.t0 = 0;
    m.p0 = random_vec(rng, 1).normalized() * 0.15;
    m.v0 = -m.p0.normalized() * uniform(rng, 1, 60) + random_vec(rng, 5);  // toward the cluster, mostly
    m.a = Vec3(0, 0, -9.81);
    m.axis0 = random_vec(rng, 1).normalized();
    m.spin = random_vec(rng, 1).cross(m.axis0).normalized() * uniform(rng, 0, 2000);
    const double until = 0.3 / m.v0.norm();
    Vec3 lo, hi;
    flight::swept_box(m, nail, 0.0, until, lo, hi);
    std::array<std::uint32_t, 64> faces{};
    const std::size_t n = scene.faces_in_box(lo, hi, faces.data(), faces.size());
    REQUIRE(n <= faces.size());
    flight::FaceSearchStats stats;
    const auto touch = flight::first_face_touch(scene, faces.data(), n, m, nail, 0.0, until, flight::FaceFilter{&scene}, stats);
    REQUIRE_FALSE(stats.gave_up);
    // The scan: the capsule against every face (CGAL's distances), stepping by what its
    // fastest point could cover of the gap (but 2 um of motion at most near a face).
    const double fastest = std::max(m.v0.norm(), (m.v0 + until * m.a).norm()) + nail.half_segment() * m.spin.norm();
    double first = HUGE_VAL;
    for (double t = 0; t <= until;) {
      Vec3 c, a;
      pose(m, t, c, a);
      const double depth = scene::deepest_overlap(soup, c, a, nail.half_segment(), 1.0).depth - (1.0 - nail.radius());
      if (depth >= -flight::kFaceTolerance) {
        first = t;
        break;
      }
      t += std::max(-depth - flight::kFaceTolerance, 2e-6) / fastest;
    }
    if (first == HUGE_VAL) {
      CHECK_FALSE(touch);
      misses += touch.has_value();
      continue;
    }
    ++touches;
    REQUIRE(touch);
    // Found at the scan's first touch, to within a step of the scan and the tolerance.
    CHECK(std::abs(touch->time - first) * fastest <= 2 * flight::kFaceTolerance + 2e-6);
    Vec3 c, a;
    pose(m, touch->time, c, a);
    const auto o = scene::deepest_overlap(soup, c, a, nail.half_segment(), nail.radius());
    CHECK(o.depth <= 1e-9);
    CHECK(o.depth >= -flight::kFaceTolerance - 1e-9);
    CHECK(touch->normal.norm() == Approx(1.0));
  }
  INFO(touches << " touches in 300 motions");
  CHECK(touches > (grit ? 40 : 100));  // (grit, smaller, misses more of the random faces)
  CHECK(misses == 0);
}

TEST_CASE("face touch: the edges inside a flat surface of many faces are not edges to a capsule sliding or falling on it",
          "[flight][contact]") {
  // A flat fan of 12 triangles about the origin, each its own face (its corners in an order
  // the scene does not take two at a time as quads); a nail lying on it, sunk 5 um (within
  // what a face being left allows), slides across the fan's edges: meeting a neighbour's edge
  // would throw it off at that edge's angle.
  scene::Soup soup;
  const auto centre = soup.add_point(Vec3::Zero());
  std::array<std::uint32_t, 12> rim{};
  for (std::size_t k = 0; k < rim.size(); ++k)
    rim[k] = soup.add_point(Vec3(0.3 * std::cos(2 * M_PI * static_cast<double>(k) / 12), 0.3 * std::sin(2 * M_PI * static_cast<double>(k) / 12), 0));
  for (std::size_t k = 0; k < rim.size(); ++k) soup.add_triangle(rim[k], rim[(k + 1) % rim.size()], centre, scene::Surface::Housing);
  const scene::Scene scene(soup, scene::Engine::Cgal);
  for (std::uint32_t f = 0; f < rim.size(); ++f) REQUIRE(scene.face_quad(f) == nullptr);
  const auto nail = projectile::Projectile::capsule(0.0508, 0.00287, 0.0021);
  std::mt19937_64 rng(17);
  int falls = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const bool falling = trial % 2 == 1;
    strike::Motion m;
    m.t0 = 0;
    const double heading = uniform(rng, 0, 2 * M_PI);
    const Vec3 along(std::cos(heading), std::sin(heading), 0);
    m.p0 = Vec3(uniform(rng, -0.05, 0.05), uniform(rng, -0.05, 0.05), nail.radius() - (falling ? -1e-4 : 5e-6)) - 0.12 * along;
    m.v0 = uniform(rng, 0.5, 20) * along + Vec3(0, 0, falling ? -uniform(rng, 0.01, 2) : 0.0);
    m.a = falling ? Vec3(0, 0, -9.81) : Vec3::Zero();
    const double yaw = uniform(rng, 0, 2 * M_PI);
    m.axis0 = Vec3(std::cos(yaw), std::sin(yaw), 0);
    m.spin = falling ? Vec3(0, 0, uniform(rng, -50, 50)) : Vec3::Zero();
    const double until = 0.24 / m.v0.norm();
    std::array<std::uint32_t, 32> faces{};
    Vec3 lo, hi;
    flight::swept_box(m, nail, 0.0, until, lo, hi);
    const std::size_t n = scene.faces_in_box(lo, hi, faces.data(), faces.size());
    flight::FaceSearchStats stats;
    const auto touch = flight::first_face_touch(scene, faces.data(), n, m, nail, 0.0, until, flight::FaceFilter{&scene}, stats);
    REQUIRE_FALSE(stats.gave_up);
    if (!falling) {
      CHECK_FALSE(touch);  // sliding on the plane: nothing to meet
      continue;
    }
    // Falling onto it across the fan's edges: met on the plane, its normal the plane's.
    REQUIRE(touch);
    ++falls;
    CHECK(touch->normal.z() > 1 - 1e-9);
    for (int k = 0; k < touch->point_count; ++k) CHECK(touch->points[static_cast<std::size_t>(k)].normal.z() > 1 - 1e-9);
  }
  CHECK(falls == 200);
}

TEST_CASE("face touch: an edge beyond a gap in a flat surface, or between two materials, is still an edge", "[flight][contact]") {
  // Two coplanar squares, side by side along x, `gap` apart; a 10 mm ball slides from the first
  // toward the second, sunk 5 um: over the gap nothing lies under it, so the second's edge is
  // met as an edge; with no gap and one material the edge is inside the surface and is not met;
  // with no gap between two materials (a skirt over a guard) it is met as before.
  const auto run = [](double gap, scene::Surface second) {
    scene::Soup soup;
    const auto square = [&](double x0, scene::Surface label) {
      const auto a = soup.add_point(Vec3(x0, -0.1, 0)), b = soup.add_point(Vec3(x0 + 0.1, -0.1, 0));
      const auto c = soup.add_point(Vec3(x0 + 0.1, 0.1, 0)), d = soup.add_point(Vec3(x0, 0.1, 0));
      soup.add_quad(a, b, c, d, label);
    };
    square(-0.1, scene::Surface::Housing);
    square(gap, second);
    const scene::Scene scene(soup, scene::Engine::Cgal);
    const auto ball = projectile::Projectile::sphere(0.01, 1e-3);
    strike::Motion m;
    m.t0 = 0, m.p0 = Vec3(-0.05, 0.01, ball.radius() - 5e-6), m.v0 = Vec3(2, 0, 0), m.a = Vec3::Zero();
    m.axis0 = Vec3::UnitX(), m.spin = Vec3::Zero();
    std::array<std::uint32_t, 8> faces{};
    Vec3 lo, hi;
    flight::swept_box(m, ball, 0.0, 0.05, lo, hi);
    const std::size_t n = scene.faces_in_box(lo, hi, faces.data(), faces.size());
    flight::FaceSearchStats stats;
    return flight::first_face_touch(scene, faces.data(), n, m, ball, 0.0, 0.05, flight::FaceFilter{&scene}, stats);
  };
  CHECK_FALSE(run(0.0, scene::Surface::Housing));
  const auto beyond_gap = run(0.005, scene::Surface::Housing);
  REQUIRE(beyond_gap);
  CHECK(beyond_gap->point.x() == Approx(0.005).margin(1e-9));
  CHECK(beyond_gap->normal.x() < -0.01);
  CHECK(run(0.0, scene::Surface::Guard));
}

TEST_CASE("face touch: a capsule sliding along a face it touches is no touch; turning into it is", "[flight][contact]") {
  // A floor (two triangles) and the capsule lying on it, its lowest point within the tolerance.
  scene::Soup soup;
  const auto a = soup.add_point({-1, -1, 0}), b = soup.add_point({1, -1, 0}), c = soup.add_point({1, 1, 0}), d = soup.add_point({-1, 1, 0});
  soup.add_quad(a, b, c, d, scene::Surface::Ground);
  const scene::Scene scene(soup);
  const auto nail = projectile::Projectile::capsule(0.0508, 0.00287, 0.0021);
  strike::Motion m;
  m.p0 = {0, 0, nail.radius() + 1e-6};
  m.v0 = {3, 0, 0};
  m.a = {-2, 0, 0};
  m.axis0 = Vec3::UnitY();
  const std::array<std::uint32_t, 2> faces{0, 1};
  flight::FaceSearchStats stats;
  CHECK_FALSE(flight::first_face_touch(scene, faces.data(), 2, m, nail, 0.0, 1.0, flight::FaceFilter{&scene}, stats));
  CHECK(stats.steps < 50);
  // Turning about its length's other axis: one end comes down into the floor at once.
  m.spin = {0, 0, 0};
  m.spin = Vec3::UnitX() * 5.0;
  stats = {};
  const auto touch = flight::first_face_touch(scene, faces.data(), 2, m, nail, 0.0, 1.0, flight::FaceFilter{&scene}, stats);
  REQUIRE(touch);
  CHECK(touch->time < 1e-3);
  CHECK(touch->normal.z() == Approx(1.0));
}

namespace {
// A sheet, the plane y = 0 above z = 0.02 (its lower edge along x), of the given surface.
scene::Soup sheet(scene::Surface surface) {
  scene::Soup soup;
  const auto a = soup.add_point({-0.1, 0, 0.02}), b = soup.add_point({0.1, 0, 0.02}), c = soup.add_point({0.1, 0, 0.1}), d = soup.add_point({-0.1, 0, 0.1});
  soup.add_quad(a, b, c, d, surface);
  return soup;
}
// A nail across under the sheet's lower edge, `sunk` into it, turning at 40 rad/s about an axis
// along the edge through its centre.
strike::Motion turning_under_sheet(const projectile::Projectile& nail, double sunk) {
  strike::Motion m;
  m.p0 = {0, 0, 0.02 - (nail.radius() - sunk)};
  m.v0 = Vec3::Zero(), m.a = Vec3::Zero();
  m.axis0 = Vec3::UnitY();
  m.spin = Vec3::UnitX() * 40.0;
  return m;
}
}  // namespace

TEST_CASE("face touch: a face being left whose slack is all but spent gets it afresh, not a touch nanoseconds on", "[flight][contact]") {
  // A sheet (the plane y = 0 above z = 0.02) and a nail across under its lower edge, sunk into
  // it within a nanometre of the slack a face being left may be entered by, turning about an
  // axis along the edge through the nail's centre: the point under the edge stands still (the
  // face is being left), while the ends swing at h w, so the bound on the nanometre left is a
  // nanosecond. Renewed only at a bound of exactly zero, the search touched the face a
  // nanosecond on; at a flap of restitution 0 that repeated 100 000 times and cut the nail off
  // (tests/test_deck.cpp). Now the slack counts again from where the capsule is.
  const scene::Scene scene(sheet(scene::Surface::Housing));
  const auto nail = projectile::Projectile::capsule(0.0508, 0.00287, 0.0021);
  const double sunk = flight::kLeavingSlack - 1e-9;
  const strike::Motion m = turning_under_sheet(nail, sunk);
  REQUIRE(flight::face_clearance(scene, 0, nail, m.p0, m.axis0) == Approx(-sunk).margin(1e-12));
  const std::array<std::uint32_t, 1> faces{0};
  flight::FaceSearchStats stats;
  const auto touch = flight::first_face_touch(scene, faces.data(), 1, m, nail, 0.0, 0.01, flight::FaceFilter{&scene}, stats);
  REQUIRE(touch);  // the tilting nail comes down onto the edge
  CHECK(touch->time > 1e-6);  // (a nanosecond before)
  CHECK(stats.steps < 10);
  Vec3 centre, axis;
  pose(m, touch->time, centre, axis);
  CHECK(flight::face_clearance(scene, 0, nail, centre, axis) > -2 * flight::kLeavingSlack);
}

TEST_CASE("face touch: a capsule deeper than kDeepestSink in a face it is leaving ends the search, below where it started", "[flight][contact]") {
  // The sheet and turning nail above, sunk a micrometre deeper than renewed slacks may take a
  // capsule (which, with the slack on top, would be past the 0.1 mm the audit allows): in a
  // test the search gives up (the flight cuts the nail off, counted); at the board, whose touch
  // ends the flight, it goes on; a field's object that started that deep in the face (placed
  // pressed into it) goes on, and one that started clear of it, or in another face, does not.
  enum class Start { Test, PressedHere, PressedElsewhere, Clear };
  for (const auto& [start, surface] : {std::pair{Start::Test, scene::Surface::Housing}, std::pair{Start::PressedHere, scene::Surface::Housing},
                                       std::pair{Start::PressedElsewhere, scene::Surface::Housing}, std::pair{Start::Clear, scene::Surface::Housing},
                                       std::pair{Start::Test, scene::Surface::TargetOutside}}) {
    CAPTURE(static_cast<int>(start), scene::name(surface));
    const scene::Scene scene(sheet(surface));
    const auto nail = projectile::Projectile::capsule(0.0508, 0.00287, 0.0021);
    for (const double sunk : {flight::kDeepestSink - 1e-6, flight::kDeepestSink + 1e-6}) {
      CAPTURE(sunk);
      const strike::Motion m = turning_under_sheet(nail, sunk);
      REQUIRE(flight::face_clearance(scene, 0, nail, m.p0, m.axis0) == Approx(-sunk).margin(1e-12));
      const std::array<std::uint32_t, 1> faces{0};
      flight::FaceFilter filter{&scene};
      flight::StartDepths started;  // (as a field's flight records them at its start)
      if (start == Start::PressedHere) started.add(0, sunk, false);
      if (start == Start::PressedElsewhere) started.add(7, sunk, false);
      if (start != Start::Test) filter.start_depths = &started;
      flight::FaceSearchStats stats;
      const auto touch = flight::first_face_touch(scene, faces.data(), 1, m, nail, 0.0, 0.01, filter, stats);
      const bool gives_up = start != Start::PressedHere && surface == scene::Surface::Housing && sunk > flight::kDeepestSink;
      CHECK(stats.sank == gives_up);
      if (gives_up) CHECK_FALSE(touch);
      CHECK_FALSE(stats.gave_up);
    }
  }
}

TEST_CASE("face touch: start depths count per face, the soil's for every ground face, the deepest for all past the list", "[flight][contact]") {
  flight::StartDepths d;
  d.add(3, 2e-4, false);
  d.add(3, 1e-4, false);  // the deeper kept
  d.add(5, 3e-4, true);
  CHECK(d.of(3, false) == 2e-4);
  CHECK(d.of(5, true) == 3e-4);
  CHECK(d.of(9, true) == 3e-4);  // another ground face: the soil is one medium
  CHECK(d.of(9, false) == 0.0);
  for (std::uint32_t f = 10; f < 20; ++f) d.add(f, 1e-5, false);
  CHECK(d.overflow);
  CHECK(d.of(42, false) == 3e-4);  // past the list: never cut off for a depth not kept
}

TEST_CASE("audit: a stretch through a face is found, to the depth it reaches", "[flight][audit]") {
  scene::Soup soup;
  const auto a = soup.add_point({0.1, -1, -1}), b = soup.add_point({0.1, 1, -1}), c = soup.add_point({0.1, 0, 1});
  soup.add_triangle(a, b, c, scene::Surface::Housing);
  const auto nail = projectile::Projectile::capsule(0.0508, 0.00287, 0.0021);
  flight::FlightStretch s;
  s.motion.p0 = {0, 0, 0}, s.motion.v0 = {10, 0, 0}, s.motion.axis0 = Vec3::UnitY();
  s.from = 0, s.until = 0.0099;  // the centre ends 1 mm short of the wall: 0.44 mm into it
  const auto through = flight::audit_flight(soup, nail, {s}, {}, 32);
  CHECK(through.deepest == Approx(nail.radius() - 0.001).margin(1e-9));
  CHECK_FALSE(through.passed());
  s.until = 0.0085;  // clear by 0.06 mm
  const auto clear = flight::audit_flight(soup, nail, {s}, {}, 32);
  CHECK(clear.deepest < 0);
  CHECK(clear.passed());
  // A bounce that gains energy is counted.
  flight::FlightEvent e;
  e.kind = flight::FlightEvent::Kind::Bounce, e.energy_before = 1.0, e.energy_after = 1.001;
  CHECK(flight::audit_flight(soup, nail, {}, {e}).energy_gains == 1);
}
