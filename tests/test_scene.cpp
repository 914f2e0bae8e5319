// The scene: ray queries against the generated J232 set-up, user meshes (and their
// errors), export, and a geometry case with a known answer for the operator zone.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <sstream>

#include "flight/nail_flight.hpp"
#include "scene/j232_setup.hpp"
#include "scene/markers.hpp"
#include "scene/mesh_io.hpp"
#include "scene/operator_zone.hpp"
#include "scene/scene.hpp"
#include "units/arc.hpp"
#include "units/quantity.hpp"

using namespace j232;
using scene::Vec3;

namespace {
scenario::Scenario basic() {
  scenario::Scenario s;
  s.spindles[0].blade.omega = 100;
  s.spindles[0].blade.hub.bar_mass = 10;
  s.spindles[0].blade.hub.bar_length = 1.2;  // tip radius 0.6
  s.housing.deck_radius = 0.65;
  return s;
}

std::string write(const std::string& name, const std::string& text) {
  std::ofstream(name) << text;
  return name;
}
}  // namespace

TEST_CASE("scene: rays meet the generated deck, skirt, ground and board where they are", "[scene]") {
  const auto s = basic();
  const scene::Scene sc(scene::build_scene_soup(s));
  const Vec3 blade(0, 0, s.spindles[0].geometry.height);
  const auto side = sc.first_hit(blade, Vec3(1, 0, 0), 10);
  REQUIRE(side);
  CHECK(side->surface == scene::Surface::Housing);
  CHECK(side->distance == Approx(0.65).epsilon(1e-3));  // 96-gon skirt: within its sagitta
  CHECK(side->normal.x() < -0.99);                      // faces back at the ray
  const auto up = sc.first_hit(blade, Vec3(0, 0, 1), 10);
  REQUIRE(up);
  CHECK(up->point.z() == Approx(s.housing.skirt_bottom + s.housing.skirt_depth));
  const auto down = sc.first_hit(blade, Vec3(0, 0, -1), 10);
  REQUIRE(down);
  CHECK(down->surface == scene::Surface::Ground);
  CHECK(down->distance == Approx(s.spindles[0].geometry.height));
  // Under the skirt, out to the board.
  const auto low = sc.first_hit(Vec3(0, 0, 0.01), Vec3(1, 0, 0), 10);
  REQUIRE(low);
  CHECK(scene::is_target(low->surface));
  CHECK(low->distance == Approx(0.6 + 0.61).epsilon(1e-3));
  // Too short a ray meets nothing; a skipped face is passed through.
  CHECK_FALSE(sc.first_hit(blade, Vec3(1, 0, 0), 0.5));
  // Along +x the ray meets the skirt on the edge its two faces share: the lower face
  // number is the answer, and the other face at the same distance once that is skipped.
  scene::Skip skip;
  skip.add(side->face);
  const auto twin = sc.first_hit(blade, Vec3(1, 0, 0), 10, skip);
  REQUIRE(twin);
  CHECK(twin->distance == side->distance);
  CHECK(twin->face > side->face);
  // Off the edge, a skipped face is passed through to what lies beyond.
  const Vec3 off_edge = Vec3(1, 0.02, 0).normalized();
  const auto inner = sc.first_hit(blade, off_edge, 10);
  REQUIRE(inner);
  scene::Skip pass;
  pass.add(inner->face);
  const auto next = sc.first_hit(blade, off_edge, 10, pass);
  REQUIRE(next);
  CHECK(next->distance > inner->distance + 0.1);
}

TEST_CASE("scene: user meshes are read, scaled and labelled; bad ones are refused", "[scene][mesh]") {
  const auto obj = write("scene-test-quad.obj", "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nf 1 2 3 4\n");
  const auto soup = scene::read_mesh(obj, scene::Surface::Housing, 0.1);
  CHECK(soup.triangles.size() == 2);
  CHECK(soup.points[2].x() == Approx(1.0));
  CHECK(soup.labels[0] == scene::Surface::Housing);

  const auto degenerate = write("scene-test-degenerate.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n3 0 1 2\n3 0 1 3\n");
  CHECK_THROWS_WITH(scene::read_mesh(degenerate, scene::Surface::Housing, 1.0),
                    Catch::Contains("scene-test-degenerate.off: face 2 is degenerate"));
  CHECK_THROWS_WITH(scene::read_mesh("no-such-mesh.stl", scene::Surface::Housing, 1.0), Catch::Contains("no such mesh file"));
  const auto text = write("scene-test-mesh.txt", "hello\n");
  CHECK_THROWS_WITH(scene::read_mesh(text, scene::Surface::Housing, 1.0), Catch::Contains("unknown mesh format"));
  // Plain OFF with comments and a colour after a face's corners; a huge index after a
  // comment on the OFF line: the counts are the next line's (CGAL's own scanner read that
  // file differently and overflowed on the index).
  const auto coloured = write("scene-test-coloured.off", "OFF # a quad\n# counts\n4 1 0\n0 0 0\n2 0 0\n2 2 0\n0 2 0 # last\n4 0 1 2 3 255 0 0\n");
  const auto quad = scene::read_mesh(coloured, scene::Surface::Guard, 0.5);
  CHECK(quad.triangles.size() == 2);
  CHECK(quad.points[2].y() == Approx(1.0));
  const auto huge = write("scene-test-huge.off", "OFF#5 4 0\n0 0 0\n1 0 0\n0 0 0 1 2 0 1\n4 3 24444444444444444444444\n");
  CHECK_THROWS_WITH(scene::read_mesh(huge, scene::Surface::Housing, 1.0), Catch::Contains("scene-test-huge.off: the mesh has no faces"));
  const auto broken = write("scene-test-broken.off", "OFF\n3 1 0\n0 0 0\n1 0\n");
  CHECK_THROWS_WITH(scene::read_mesh(broken, scene::Surface::Housing, 1.0), Catch::Contains("scene-test-broken.off"));
  for (const char* f : {"scene-test-quad.obj", "scene-test-degenerate.off", "scene-test-mesh.txt", "scene-test-broken.off",
                        "scene-test-coloured.off", "scene-test-huge.off"})
    std::remove(f);
}

TEST_CASE("scene: export writes a labelled PLY and a grouped OBJ that read back, with the mower's lines", "[scene][export]") {
  const auto s = basic();
  const auto soup = scene::build_scene_soup(s);
  const auto markers = scene::mower_markers(s);
  // One tip circle per spindle, one line per feed station, the seat's three arms and three
  // great circles for each of the derived zone's three reach spheres.
  std::map<std::string, std::size_t> groups;
  for (const auto& m : markers) ++groups[m.group];
  CHECK(groups["tip_circles"] == s.spindles.size());
  CHECK(groups["feed_stations"] == s.feed_station_count());
  CHECK(groups["seat"] == 3);
  CHECK(groups["reach_envelope"] == 9);
  for (const auto& m : markers)
    if (m.group == "tip_circles")
      for (const auto& p : m.points) CHECK(std::hypot(p.x(), p.y()) == Approx(s.spindles[0].blade.tip_radius()));
  auto lines = markers;
  lines.push_back({"nail_paths", {0, 114, 178}, {{0.5, 0, 0.08}, {1.0, 0.2, 0.1}, {1.2, 0.3, 0.12}}, false});
  for (const std::string ext : {".ply", ".obj"}) {
    const std::string file = "scene-test-export" + ext;
    const std::string text = scene::export_text(soup, lines, file);
    std::ofstream(file) << text;
    // Mesh readers take the surfaces and skip the lines.
    CHECK(scene::read_mesh(file, scene::Surface::Housing, 1.0).triangles.size() == soup.triangles.size());
    std::size_t vertices = soup.points.size(), segments = 0;
    for (const auto& l : lines) vertices += l.points.size(), segments += l.points.size() - 1 + (l.closed ? 1 : 0);
    std::istringstream in(text);
    std::size_t v = 0, edges = 0, polyline_segments = 0;
    std::size_t highest = 0;
    for (std::string line; std::getline(in, line);) {
      std::istringstream words(line);
      std::string head;
      words >> head;
      if (head == "v") ++v;
      if (head == "l") {
        std::size_t i = 0, n = 0;
        while (words >> i) highest = std::max(highest, i), ++n;
        polyline_segments += n - 1;
      }
      if (line.rfind("element vertex ", 0) == 0) v = std::stoul(line.substr(15));
      if (line.rfind("element edge ", 0) == 0) edges = std::stoul(line.substr(13));
    }
    CHECK(v == vertices);
    if (ext == ".obj") {
      CHECK(polyline_segments == segments);
      CHECK(highest == vertices);  // OBJ counts from 1: the last line point is the last vertex
      CHECK(text.find("g operator_zone") != std::string::npos);
      CHECK(text.find("g ground") != std::string::npos);
      CHECK(text.find("g reach_envelope") != std::string::npos);
      CHECK(text.find("g nail_paths") != std::string::npos);
    } else {
      CHECK(edges == segments);
      // The last edge is the path's last segment: its last two vertices.
      const auto last = text.substr(text.rfind('\n', text.size() - 2) + 1);
      CHECK(last.rfind(fmt::format("{} {} 0 114 178", vertices - 2, vertices - 1), 0) == 0);
    }
    std::remove(file.c_str());
  }
  CHECK_THROWS_AS(scene::export_text(soup, lines, "scene-test-export.xyz"), std::invalid_argument);
}

TEST_CASE("scene: the operator-zone share converges to the sector's fraction of the ring", "[scene][zone][statistics][long]") {
  // Nails thrown in the blade plane with uniformly random azimuth at a ring of board
  // whose operator zone spans 80 deg: the zone's share of the marks is 80/360.
  auto s = basic();
  s.zone.kind = scenario::OperatorZoneSpec::Kind::Sector;
  s.zone.azimuth.from = -0.5;
  s.zone.azimuth.to = -0.5 + 80 * units::pi / 180;
  s.zone.bottom = 0;
  s.zone.top = 2;
  scene::Soup soup = scene::build_scene_soup(s), ring;
  // Keep only the board: nothing else in the way.
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (scene::is_target(soup.labels[t])) {
      const auto& tri = soup.triangles[t];
      ring.add_triangle(ring.add_point(soup.points[tri[0]]), ring.add_point(soup.points[tri[1]]), ring.add_point(soup.points[tri[2]]),
                        soup.labels[t]);
    }
  const scene::Scene sc(ring);
  const flight::FlightSettings settings(s, std::vector<scenario::GuardSpec>(1));
  const flight::FlightContext ctx{&sc, &settings, 100.0, 0.65, 0.0};
  int zone = 0, marks = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    random::Stream rng(17, 0, static_cast<std::uint64_t>(i), random::Purpose::Test);
    const double a = 2 * units::pi * rng.uniform();
    flight::Body b;
    b.position = {0, 0, s.spindles[0].geometry.height};
    b.velocity = {100 * std::cos(a), 100 * std::sin(a), 0};
    b.axis = Vec3::UnitZ();  // broadside to the board
    random::EventDraws draws(17, 0, static_cast<std::uint64_t>(i));
    const auto r = flight::fly(b, projectile::Projectile::capsule(0.0508, 0.00251, 0.002), {}, ctx, {}, {}, draws);
    marks += r.mark_count;
    zone += r.hits_zone + r.punctures_zone;
  }
  REQUIRE(marks == n);  // 10 J broadside against a 5.6 J puncture threshold: every nail marks
  const double p = 80.0 / 360.0, share = static_cast<double>(zone) / marks;
  CHECK(std::abs(share - p) < 4 * std::sqrt(p * (1 - p) / marks));
}

TEST_CASE("counted height: J232 counts only marks above the blade plane", "[scene][board]") {
  // Nails thrown level at the board from the blade plane, 5 cm above and 5 cm below the
  // counted height: the marks are located either way, but only the upper ones count.
  const auto s = basic();
  const scene::Scene sc(scene::build_scene_soup(s));
  const flight::FlightSettings settings(s, std::vector<scenario::GuardSpec>(1));
  const double counted = s.spindles[0].geometry.height;
  const flight::FlightContext ctx{&sc, &settings, 100.0, 0.65, counted};
  for (const double dz : {0.05, -0.05}) {
    random::EventDraws rng(3, 0, 0);
    flight::Body b;
    b.position = {0.9, 0, counted + dz};  // outside the deck, inside the board
    b.velocity = {100, 0, 0};
    b.axis = Vec3::UnitZ();
    const auto r = flight::fly(b, projectile::Projectile::capsule(0.0508, 0.00251, 0.002), {}, ctx, {}, {}, rng);
    REQUIRE(r.mark_count == 1);
    CHECK(r.marks[0].counted == (dz > 0));
    CHECK(r.uncounted_marks == (dz > 0 ? 0 : 1));
    CHECK(r.hits_zone + r.punctures_zone + r.hits_outside + r.punctures_outside == (dz > 0 ? 1 : 0));
    CHECK(r.fate == (dz > 0 ? flight::Fate::MarkedBoard : flight::Fate::MarkedBelowCountedHeight));
  }
}

TEST_CASE("operator zone: derived from the reach envelope of a seated operator", "[scene][zone]") {
  scenario::OperatorZoneSpec spec;  // seat 2 m ahead of the spindle, 0.9 m up
  const scene::OperatorZone zone(spec, 0.076);
  // A board point straight between the blade and the operator's shoulders is in the zone...
  CHECK(zone.contains(Vec3(1.2, 0.0, 0.6)));
  // ...one behind the mower, or low at the side facing away, is not.
  CHECK_FALSE(zone.contains(Vec3(-1.2, 0.0, 0.3)));
  CHECK_FALSE(zone.contains(Vec3(0.0, 1.2, 0.05)));
}

// One set of arc rules for openings, guards, the board's pieces, the exit's opening and a
// sector zone (units/arc.hpp): counter-clockwise from the start, the start included and the
// end not, a whole turn when the end is 360 deg past the start.
TEST_CASE("arcs: one rule for every stage, the start in and the end out", "[scene][zone][arc]") {
  CHECK(units::in_arc(0.1, -0.5, 0.5));
  CHECK(units::in_arc(3.1, 3.0, -3.0));  // wraps through pi
  CHECK(units::in_arc(-3.1, 3.0, -3.0));
  CHECK_FALSE(units::in_arc(0.0, 3.0, -3.0));
  CHECK(units::in_arc(1.0, 0.0, 2 * units::pi));  // the whole turn
  CHECK(units::in_arc(-0.5, -0.5, 0.5));          // the start is in
  CHECK_FALSE(units::in_arc(0.5, -0.5, 0.5));     // the end is out: arcs that meet share no azimuth
  CHECK(units::in_arc(0.5, 0.5, 1.0));
  CHECK(units::in_arc(0.5 + 2 * units::pi, -0.5, 1.0));  // azimuths a turn apart are one
  CHECK(units::arc_span(1.0, 1.0 - 0.5) == Approx(2 * units::pi - 0.5));
  // A whole turn written as 360 deg past the start, whatever the rounding of the radians
  // (420 deg - 60 deg is 2 pi + 9e-16: a remainder alone made it an arc of nothing).
  for (const double from_deg : {0.0, 20.0, 60.0, 135.0, -90.0}) {
    const double from = from_deg * units::pi / 180, to = (from_deg + 360) * units::pi / 180;
    CHECK(units::arc_span(from, to) == 2 * units::pi);
    CHECK(units::arc_span(to, from) == 2 * units::pi);
    for (double a = -3.0; a < 3.2; a += 0.5) CHECK(units::in_arc(a, from, to));
  }
  CHECK(units::arcs_overlap(0.0, 1.0, 0.5, 2.0));
  CHECK_FALSE(units::arcs_overlap(0.0, 1.0, 1.0, 2.0));  // meeting at an end only
  // The Arc the scenario's parts carry answers by the same rules.
  const units::Arc wrap{3.0, -3.0}, meets{1.0, 2.0};
  CHECK(wrap.contains(3.1));
  CHECK_FALSE(wrap.contains(0.0));
  CHECK(wrap.span() == Approx(2 * units::pi - 6.0));
  CHECK(wrap.middle() == Approx(units::pi));
  CHECK(wrap.offset(-3.1) == Approx(2 * units::pi - 6.1));
  CHECK(units::Arc{0.0, 1.0}.overlaps(units::Arc{0.5, 2.0}));
  CHECK_FALSE(units::Arc{0.0, 1.0}.overlaps(meets));
  CHECK(units::Arc{0.0, 0.0}.span() == 2 * units::pi);  // from == to: the whole turn
  // A sector zone judges by the same rule (it had its own, with the end included).
  scenario::OperatorZoneSpec spec;
  spec.kind = scenario::OperatorZoneSpec::Kind::Sector;
  spec.azimuth.from = 0.0, spec.azimuth.to = units::pi / 2, spec.bottom = 0.0, spec.top = 1.0;
  const scene::OperatorZone sector(spec, 0.076);
  CHECK(sector.contains(Vec3(1.0, 0.0, 0.5)));  // at the start
  CHECK(sector.contains(Vec3(1.0, 1.0, 0.5)));
  CHECK_FALSE(sector.contains(Vec3(0.0, 1.0, 0.5)));  // at the end
  CHECK_FALSE(sector.contains(Vec3(-1.0, 0.1, 0.5)));
  CHECK_FALSE(sector.contains(Vec3(1.0, 1.0, 1.5)));  // above it
  spec.azimuth.from = 60 * units::pi / 180, spec.azimuth.to = 420 * units::pi / 180;  // the whole turn
  const scene::OperatorZone all_round(spec, 0.076);
  CHECK(all_round.contains(Vec3(1.0, 0.0, 0.5)));
  CHECK(all_round.contains(Vec3(-1.0, -0.2, 0.5)));
}

TEST_CASE("mesh: PLY headers that CGAL's reader cannot take are refused before it reads them", "[scene][mesh]") {
  auto refused = [](const std::string& text) {
    const std::string file = "scene-test-header.ply";
    std::ofstream(file, std::ios::binary) << text;
    std::string message;
    try {
      scene::read_mesh(file, scene::Surface::Housing, 1.0);
    } catch (const std::runtime_error& e) {
      message = e.what();
    }
    std::remove(file.c_str());
    return message;
  };
  const std::string vertices = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  CHECK(refused("ply\nformat ascii 1.0\n" + vertices + faces).empty());  // sound
  // Items of nothing: CGAL would loop over all of them (a fuzzing find: 10^13 items).
  CHECK_THAT(refused("ply\nformat ascii 1.0\n" + vertices + "element junk 5\n" + faces), Catch::Contains("no properties"));
  CHECK_THAT(refused("ply\nformat ascii 1.0\n" + vertices + "element junk 11111111111111\nproperty uchar a\n" + faces),
             Catch::Contains("more than the file has bytes"));
  CHECK_THAT(refused("ply\nformat ascii 1.0\nproperty float x\n" + vertices + faces), Catch::Contains("a property before any element"));
  CHECK_THAT(refused("ply\nformat ascii 1.0\n" + vertices + "element face 1\nproperty list int int vertex_indices\nend_header\n"),
             Catch::Contains("a list's count must be uchar or ushort"));
}
