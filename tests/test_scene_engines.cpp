// The two scene engines (CGAL's AABB tree, Embree's BVH) answer every ray query the same,
// bit for bit: the same face at the same distance, on the shipped scenes, for rays
// that start on surfaces as a bouncing nail's do, and for whole assessments.
// The broad phase (one box tree for both) against a scan of every face.
#include <catch2/catch.hpp>
#include <algorithm>
#include <string>
#include <vector>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "random/stream.hpp"
#include "report/result_files.hpp"
#include "scenario/scenario.hpp"
#include "scenario/scenario_reader.hpp"
#include "scene/j232_setup.hpp"
#include "scene/scene.hpp"

using namespace j232;
using scene::Vec3;

namespace {
std::string scenario_path(const char* name) { return std::string(J232_SOURCE_DIR) + "/scenarios/" + name; }

Vec3 random_direction(random::Stream& rng) {
  const double z = rng.uniform(-1, 1), a = rng.uniform(0, 6.283185307179586);
  const double r = std::sqrt(1 - z * z);
  return {r * std::cos(a), r * std::sin(a), z};
}
}  // namespace

TEST_CASE("scene engines: Embree and CGAL give identical hits on chains of queries", "[scene][engine]") {
  if (!scene::engine_available(scene::Engine::Embree)) {
    WARN("Embree is not built in: only the CGAL engine to test");
    return;
  }
  for (const char* name : {"highway-pivoted-chains.toml", "highway-meshes.toml", "deck-72in-three-spindle.toml", "batwing-15ft.toml"}) {
    const auto s = scenario::read_scenario(scenario_path(name));
    const auto soup = scene::build_scene_soup(s);
    const scene::Scene cgal(soup, scene::Engine::Cgal), embree(soup, scene::Engine::Embree);
    REQUIRE(cgal.engine() == scene::Engine::Cgal);
    REQUIRE(embree.engine() == scene::Engine::Embree);
    random::Stream rng(7, 0, 0, random::Purpose::Test);
    long queries = 0, hits = 0;
    // Like a nail's flight: start near the blade, go a chord's length, and from each hit
    // go on in a random direction away from that face, skipping it.
    for (int chain = 0; chain < 1500; ++chain) {
      Vec3 from(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(0.02, 0.3));
      scene::Skip skip;
      for (int step = 0; step < 12; ++step) {
        const Vec3 dir = random_direction(rng);
        const double reach = step % 3 == 0 ? 5.0 : rng.uniform(0.01, 0.5);
        const auto a = cgal.first_hit(from, dir, reach, skip), b = embree.first_hit(from, dir, reach, skip);
        ++queries;
        REQUIRE(a.has_value() == b.has_value());
        if (!a) {
          from += reach * dir;
          skip = {};
          continue;
        }
        ++hits;
        INFO(name << ": query " << queries << " from " << from.transpose() << " along " << dir.transpose());
        REQUIRE(a->face == b->face);
        REQUIRE(a->distance == b->distance);  // bit for bit
        from = a->point;
        skip = {};
        skip.add(a->face);
      }
    }
    INFO(name << ": " << queries << " queries, " << hits << " hits");
    CHECK(hits > 3000);  // most chains meet surfaces: the comparison is about hits
  }
}

TEST_CASE("scene engines: a whole assessment is the same with either engine", "[scene][engine][assess][long]") {
  if (!scene::engine_available(scene::Engine::Embree)) {
    WARN("Embree is not built in: only the CGAL engine to test");
    return;
  }
  auto s = scenario::read_scenario(scenario_path("deck-72in-three-spindle.toml"));
  s.run.replicates = 24;
  const report::Provenance p{"test", "test", "today", "digest", 0, 0, {}, 1};
  std::string dumps[2];
  for (int e = 0; e < 2; ++e) {
    const assess::Simulator sim(s, e == 0 ? scene::Engine::Cgal : scene::Engine::Embree);
    const auto a = assess::run_assessment(sim, 2);
    dumps[e] = report::result_json(s, a, assess::summarise(a, s), p).dump();
  }
  CHECK(dumps[0] == dumps[1]);
}

TEST_CASE("scene: the broad phase's box query gives exactly the faces a scan of every face gives, in face order", "[scene][engine]") {
  // The scan decides from the triangle's own corners, apart from the box tree.
  for (const char* name : {"highway-pivoted-chains.toml", "highway-meshes.toml", "deck-72in-three-spindle.toml"}) {
    const auto s = scenario::read_scenario(scenario_path(name));
    const auto soup = scene::build_scene_soup(s);
    const scene::Scene scene(soup, scene::Engine::Cgal);
    random::Stream rng(9, 0, 0, random::Purpose::Test);
    std::vector<std::uint32_t> got(4096), want;
    long total = 0;
    for (int q = 0; q < 600; ++q) {
      // (One draw at a time: the order a constructor's arguments are worked out in is the
      // compiler's, and clang's differs from g++'s.)
      Vec3 c, half;
      for (int k = 0; k < 3; ++k) c[k] = k < 2 ? rng.uniform(-1.2, 1.2) : rng.uniform(-0.05, 0.4);
      for (int k = 0; k < 3; ++k) half[k] = rng.uniform(0, k == 0 && q % 10 == 0 ? 0.5 : 0.05);
      const Vec3 lo = c - half, hi = c + half;
      want.clear();
      std::uint32_t skip_until = 0;  // the triangles of a plate's polygon after its first
      for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
        // A quad's second triangle is listed as its first (one face, over both boxes), and a
        // plate's polygon by its first triangle, over all its triangles' boxes.
        if (f > 0 && scene.face_quad(f - 1)) continue;
        if (f < skip_until) continue;
        const std::uint32_t members = scene.face_polygon(f) ? static_cast<std::uint32_t>(scene.face_polygon(f)->count) : scene.face_quad(f) ? 2u : 1u;
        skip_until = f + members;
        Vec3 flo = soup.points[soup.triangles[f][0]], fhi = flo;
        for (std::uint32_t t = f; t < f + members; ++t)
          for (const auto k : soup.triangles[t]) flo = flo.cwiseMin(soup.points[k]), fhi = fhi.cwiseMax(soup.points[k]);
        // (A margin of rounding either way: faces that close to the box's edge are not judged.)
        const double eps = 1e-12;
        const bool in = !((flo.array() > hi.array() + eps).any() || (fhi.array() < lo.array() - eps).any());
        const bool out = (flo.array() > hi.array() - eps).any() || (fhi.array() < lo.array() + eps).any();
        if (in && !out) want.push_back(f);
        if (in && out) want.push_back(f | 0x80000000u);  // undecided
      }
      const std::size_t n = scene.faces_in_box(lo, hi, got.data(), got.size());
      REQUIRE(n <= got.size());
      REQUIRE(std::is_sorted(got.begin(), got.begin() + static_cast<long>(n)));
      REQUIRE(std::adjacent_find(got.begin(), got.begin() + static_cast<long>(n)) == got.begin() + static_cast<long>(n));
      std::size_t i = 0;
      for (const std::uint32_t w : want) {
        const std::uint32_t f = w & 0x7fffffffu;
        const bool undecided = w & 0x80000000u;
        while (i < n && got[i] < f) FAIL("face " << got[i] << " given but outside the box");
        if (i < n && got[i] == f) {
          ++i;
        } else if (!undecided) {
          FAIL(name << ": face " << f << " meets the box but was not given");
        }
      }
      REQUIRE(i == n);
      total += static_cast<long>(n);
    }
    INFO(name << ": " << total << " faces listed in all");
    CHECK(total > 150);  // the queries did find faces
    std::size_t quads = 0, polygons = 0;
    for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) quads += scene.face_quad(f) != nullptr, polygons += scene.face_polygon(f) != nullptr;
    CHECK(quads > 50);  // and quads among them (the generated decks' panels)
    if (std::string(name) != "highway-meshes.toml") CHECK(polygons >= 1);  // and the generated deck's plate, one polygon
  }
}
