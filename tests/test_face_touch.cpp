// The capsule's contact search against the scene's real faces (flight/face_touch.hpp),
// checked against code it does not share: CGAL's distances (scene/capsule_audit.hpp) and a
// fine fixed-step scan of the motion.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>
#include <random>

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

TEST_CASE("face touch: the first touch of a tumbling capsule is a fine scan's, and it never passes through a face", "[flight][contact]") {
  std::mt19937_64 rng(11);
  // A 6d nail, and the smallest field object allowed (1 mm grit, a sphere: the capsule of no
  // length), which thin faces must stop as well.
  const bool grit = GENERATE(false, true);
  const auto nail = grit ? projectile::Projectile::sphere(0.001, 1.4e-6) : projectile::Projectile::capsule(0.0508, 0.00287, 0.0021);
  int touches = 0, misses = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const scene::Soup soup = random_soup(rng, 6);
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
