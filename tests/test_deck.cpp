// A deck of several spindles: the scenario form, clockwise blades, and a whole run.
#include <catch2/catch.hpp>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <string>
#include <toml++/toml.h>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "feed/feed.hpp"
#include "strike/contact_search.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario.hpp"
#include "scenario/scenario_reader.hpp"
#include "scenario/toml_override.hpp"
#include "scenario/toml_reader.hpp"
#include "scene/j232_setup.hpp"
#include "units/quantity.hpp"
#include "report/scenario_json.hpp"

using namespace j232;

namespace {
const std::string kBlades = R"(
[blades.bar]
speed = "2700 rpm"
[blades.bar.hub]
bar_mass = "3.5 lb"
bar_length = "25 in"
)";
const std::string kThree = kBlades + R"(
[[spindles]]
blade = "bar"
x = "0.2 m"
[[spindles]]
blade = "bar"
x = "-0.05 m"
y = "0.597 m"
sense = "cw"
phase = "30 deg"
[[spindles]]
blade = "bar"
x = "-0.05 m"
y = "-0.597 m"
phase = "0 deg"
)";

scenario::Scenario read(const std::string& text) {
  return scenario::read_scenario(toml::parse(text, std::string_view("deck.toml")), "deck.toml");
}
std::string scenario_path(const char* name) { return std::string(J232_SOURCE_DIR) + "/scenarios/" + name; }
}  // namespace

TEST_CASE("deck: [[spindles]] with named blades, positions, senses and phases", "[deck][input]") {
  const auto s = read(kThree);
  REQUIRE(s.spindles.size() == 3);
  CHECK(s.spindles[0].blade_name == "bar");
  CHECK(s.spindles[1].y == Approx(0.597));
  CHECK(s.spindles[1].sense == -1);
  CHECK(s.spindles[0].sense == +1);
  CHECK_FALSE(s.spindles[0].phase);  // untimed unless a phase is given
  CHECK(*s.spindles[1].phase == Approx(30 * units::pi / 180));
  // J232 feeds every blade: one station per spindle by default.
  CHECK_FALSE(s.feed.stations);  // none written: the defaults are derived, not stored
  REQUIRE(s.feed_station_count() == 3);
  CHECK(s.feed_station(2).spindle == 2);
  CHECK(s.feed_station(2).radius == Approx(12.5 * units::inch - 0.0508));
  CHECK(s.reach() == Approx(std::hypot(0.05, 0.597) + 12.5 * units::inch));
  CHECK(s.tip_speed() == Approx(2700 * units::rpm * 12.5 * units::inch));
}

TEST_CASE("deck: bad decks are refused with the key and what was expected", "[deck][input]") {
  using Catch::Contains;
  CHECK_THROWS_WITH(read(kThree + "[blade]\nspeed = \"1000 rpm\"\n"), Contains("give either [blade]") && Contains("not both"));
  CHECK_THROWS_WITH(read(kBlades + "[[spindles]]\nblade = \"nope\"\n"), Contains("spindles[1].blade") && Contains("[blades.nope]"));
  CHECK_THROWS_WITH(read(kBlades + "[blades.spare]\nspeed = \"1 rpm\"\n[[spindles]]\nblade = \"bar\"\n"),
                    Contains("blades.spare") && Contains("no spindle uses this blade"));
  CHECK_THROWS_WITH(read(kBlades + "[[spindles]]\nblade = \"bar\"\n[[spindles]]\nblade = \"bar\"\nx = \"0.5 m\"\n"),
                    Contains("spindles[2].x") && Contains("overlaps spindle 1"));
  CHECK_THROWS_WITH(read(kThree + "[[feed.stations]]\nspindle = 4\nradius = \"10 in\"\n"),
                    Contains("feed.stations[1].spindle") && Contains("from 1 to 3"));
  CHECK_THROWS_WITH(read(kThree + "[[feed.stations]]\nspindle = 2\nradius = \"13 in\"\n"), Contains("feed.stations[1].radius"));
  CHECK_THROWS_WITH(read(kThree + "[housing]\ndeck_radius = \"1 m\"\n"), Contains("housing.deck_radius") && Contains("margin"));
  CHECK_THROWS_WITH(read(kThree + "[[spindles]]\nblade = \"bar\"\nsense = \"up\"\n"), Contains("\"ccw\", \"cw\""));
}

TEST_CASE("deck: a clockwise blade strikes the mirror image of a counter-clockwise one", "[deck][feed]") {
  const auto s = read(kThree);
  strike::Spindle ccw(s.spindles[0].blade, s.spindles[0].geometry, s.restitution), cw = ccw;
  ccw.sense = +1, cw.sense = -1;
  feed::NailDrop d;
  d.nail = projectile::Projectile::capsule(0.0508, 0.00251, 0.002);
  d.fall_speed = 2.4;
  d.axis = Eigen::Vector3d(0.05, 0.03, 1.0).normalized();
  int struck = 0;
  for (const double phase : {0.3, 1.7, 4.0, 5.5}) {
    d.position = {0.2, 0.15};
    d.blade_phase = phase;
    const auto left = feed::fall_through(d, ccw);
    strike::SearchStats stats;
    const auto a = strike::first_contact(ccw, phase, d.nail, left.motion, left.until, stats);
    feed::NailDrop mirrored = d;
    mirrored.position = {0.2, -0.15};
    mirrored.axis.y() = -d.axis.y();
    const auto right = feed::fall_through(mirrored, cw);
    const auto b = strike::first_contact(cw, -phase, mirrored.nail, right.motion, right.until, stats);
    REQUIRE(a.has_value() == b.has_value());
    if (!a) continue;
    ++struck;
    CHECK(b->time == Approx(a->time).margin(1e-12));
    CHECK(b->point.y() == Approx(-a->point.y()).margin(1e-12));
    CHECK(b->normal.y() == Approx(-a->normal.y()).margin(1e-12));
    CHECK(b->radius == Approx(a->radius).margin(1e-12));
  }
  CHECK(struck > 0);
}

TEST_CASE("deck: the three-spindle deck runs, its outline encloses every tip circle, nails meet other blades", "[deck][assess][long]") {
  auto s = scenario::read_scenario(scenario_path("deck-72in-three-spindle.toml"));
  s.run.replicates = 100;
  // The generated skirt lies outside every tip circle, and the opening cuts it.
  const auto soup = scene::build_scene_soup(s);
  std::size_t skirt_points = 0;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (soup.labels[t] == scene::Surface::Housing)
      for (auto v : soup.triangles[t]) {
        const auto& p = soup.points[v];
        if (p.z() > s.housing.skirt_bottom + s.housing.skirt_depth - 1e-9) continue;  // the plate: only the skirt's foot
        // (The outline is the hull of 96-gons about each tip circle widened by the margin:
        // a point on a side lies within r (1 - cos(pi / 96)) of that circle.)
        for (const auto& sp : s.spindles)
          CHECK(std::hypot(p.x() - sp.x, p.y() - sp.y) >= (sp.blade.tip_radius() + s.housing.margin) * std::cos(units::pi / 96) - 1e-9);
        ++skirt_points;
      }
  CHECK(skirt_points > 100);
  const assess::Simulator sim(s);
  const auto a = assess::run_assessment(sim, 2);
  const auto sum = assess::summarise(a, s);
  CHECK(sum.validity.valid);
  CHECK(a.struck > a.nails / 2);
  CHECK(a.strikes.mean() > 1.2);  // thrown into the neighbouring blades' discs
  // ...and the same on one thread, bit for bit.
  const auto one = assess::run_assessment(sim, 1);
  CHECK(one.strikes.counts == a.strikes.counts);
  CHECK(one.shares[assess::PuncturesOutside].counts == a.shares[assess::PuncturesOutside].counts);
}

TEST_CASE("deck: a discharge chute roofs its opening, runs outward and keeps nails low", "[deck][housing][long]") {
  auto s = scenario::read_scenario(scenario_path("deck-72in-three-spindle.toml"));
  REQUIRE(s.housing.openings.size() == 1);
  const auto& o = s.housing.openings[0];
  REQUIRE(o.chute_length > 0);
  // The opening is on the right (azimuth -110 to -70 deg): the chute runs toward -y from the
  // outline (outer spindle at y -0.597 m, tip circle + margin) for chute_length.
  const double outline_y = -0.597 - s.spindles[2].blade.tip_radius() - s.housing.margin;
  const auto soup = scene::build_scene_soup(s);
  double lowest_y = 0;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (soup.labels[t] == scene::Surface::Housing)
      for (auto v : soup.triangles[t]) {
        const auto& p = soup.points[v];
        if (p.y() < outline_y - 0.01) {  // part of the chute: between the skirt's foot and its roof
          CHECK(p.z() >= s.housing.skirt_bottom - 1e-12);
          CHECK(p.z() <= s.housing.opening_top(o) + 1e-12);
        }
        lowest_y = std::min(lowest_y, p.y());
      }
  CHECK(lowest_y == Approx(outline_y - o.chute_length).margin(0.005));
  // The same deck with and without its chute, on the same random numbers: the chute turns
  // the nails that leave by the opening down into the turf, so far fewer of the marks come
  // by the opening. (Most of this deck's marks come from nails that the blade's faces send
  // down into the turf and out under the skirt: docs/validation.md.)
  s.run.replicates = 100;
  auto open = s;
  open.housing.openings[0].chute_length = 0;
  const auto by_opening = [](const assess::Assessment& a) {
    std::uint64_t marks = 0;
    for (const auto& [key, bands] : a.exits.marks)
      if (a.exit_names.at(key).rfind("opening", 0) == 0)
        for (auto n : bands) marks += n;
    return marks;
  };
  const auto with = assess::run_assessment(assess::Simulator(s), 2), without = assess::run_assessment(assess::Simulator(open), 2);
  INFO("marks by the opening: " << by_opening(with) << " with the chute, " << by_opening(without) << " without");
  CHECK(by_opening(without) > 100);
  // 196 against 602 when written (the nail bouncing as a point), 440 against 827 since it
  // bounces as a tumbling rod (its spin feeds its rebounds off the chute and the turf).
  CHECK(5 * by_opening(with) < 3 * by_opening(without));
}

TEST_CASE("deck: guards and deflectors along polylines hang on a mesh deck too", "[deck][housing][mesh][long]") {
  using Catch::Contains;
  const std::string path = scenario_path("highway-meshes.toml");
  std::ifstream in(path);
  const std::string base((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto read_with = [&](const std::string& extra) { return scenario::read_scenario(toml::parse(base + extra, path), path); };
  // A solid curtain wrapped round the mesh deck's rear discharge opening (150-210 deg at
  // 26 in): its ends reach forward, or glancing nails would slide along it and out.
  const std::string curtain = R"(
[[housing.guards]]
name = "rear curtain"
along = [["-10 in", "-32 in"], ["-30 in", "-24 in"], ["-30 in", "24 in"], ["-10 in", "32 in"]]
top = "8.5 in"
bottom = "0 in"
openness = 0
)";
  const auto s = read_with(curtain);
  REQUIRE(s.housing.guards.size() == 1);
  CHECK(s.housing.guards[0].along.size() == 4);
  const auto soup = scene::build_scene_soup(s);
  std::size_t curtain_faces = 0;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (soup.labels[t] == scene::Surface::Guard) {
      ++curtain_faces;
      CHECK(soup.guard_index[t] == 0);
      for (auto v : soup.triangles[t]) {
        CHECK(soup.points[v].x() <= -10 * units::inch + 1e-9);
        CHECK(soup.points[v].z() <= 8.5 * units::inch + 1e-9);
      }
    }
  CHECK(curtain_faces >= 2 * (3 + 13 + 3));  // 21 + 48 + 21 in, in pieces of at most 0.1 m, two triangles each
  // It stops what the opening lets out.
  auto with = s, without = read_with("");
  with.run.replicates = without.run.replicates = 60;
  // The counted marks on the board behind the deck (x < -0.4 m: the ring behind the rear
  // opening, and the corners of the deck).
  const auto rear_marks = [](const scenario::Scenario& sc) {
    std::uint64_t marks = 0;
    assess::run_assessment(assess::Simulator(sc), 2, nullptr, [&](const assess::MarkRow& r) {
      if (r.mark.counted && r.mark.point.x() < -0.4) ++marks;
    });
    return marks;
  };
  const auto a = rear_marks(with), b = rear_marks(without);
  INFO("marks behind the deck: " << a << " with the curtain, " << b << " without");
  CHECK(b > 50);
  CHECK(5 * a < 3 * b);  // the opening's share gone; what leaves under the skirt behind stays
  // What a mesh deck has no use for is refused, naming the mesh.
  CHECK_THROWS_WITH(read_with("[[housing.guards]]\nazimuth_from = \"0 deg\"\nazimuth_to = \"90 deg\"\n"),
                    Contains("housing.guards[1].azimuth_from") && Contains("meshes/deck.obj") && Contains("along"));
  CHECK_THROWS_WITH(read_with("[[housing.guards]]\nalong = [[\"0 m\", \"1 m\"], [\"1 m\", \"1 m\"]]\n"),
                    Contains("housing.guards[1].along") && Contains("`top`"));
  CHECK_THROWS_WITH(read_with("[housing]\nskirt_bottom = \"2 in\"\n"), Contains("housing.skirt_bottom") && Contains("meshes/deck.obj"));
  // A deflector panel along a polyline is a solid wall.
  const auto d =
      read_with("[[housing.deflectors]]\nalong = [[\"-28 in\", \"-16 in\"], [\"-28 in\", \"16 in\"]]\nbottom = \"0 m\"\ntop = \"8 in\"\n");
  std::size_t panel = 0;
  const auto dsoup = scene::build_scene_soup(d);
  for (std::size_t t = 0; t < dsoup.triangles.size(); ++t) panel += dsoup.labels[t] == scene::Surface::Deflector;
  CHECK(panel >= 18);
  // Malformed paths name the key and the expected form.
  CHECK_THROWS_WITH(read_with("[[housing.deflectors]]\nalong = [[\"1 m\"]]\nbottom = \"0 m\"\ntop = \"8 in\"\n"),
                    Contains("housing.deflectors[1].along") && Contains("points [x, y]"));
  CHECK_THROWS_WITH(
      read_with("[[housing.deflectors]]\nalong = [[\"1 m\", \"2 m\"], [\"1 kg\", \"0 m\"]]\nbottom = \"0 m\"\ntop = \"8 in\"\n"),
      Contains("housing.deflectors[1].along"));
  CHECK_THROWS_WITH(
      read_with(
          "[[housing.deflectors]]\nalong = [[\"1 m\", \"2 m\"], [\"1 m\", \"0 m\"]]\nradius = \"1 m\"\nbottom = \"0 m\"\ntop = \"8 in\"\n"),
      Contains("housing.deflectors[1].radius") && Contains("not both"));
}

TEST_CASE("deck: a flap 2 mm behind an opening (a channel narrower than the nail) lets by what a flush one does", "[deck][housing][long]") {
  // The highway mower with its skirt 1/4 in above the turf, a rear opening (160-200 deg) and
  // a solid flap over it along the deck's circle (155-205 deg), flush with the skirt, 2 mm
  // outside it (a channel narrower than the nail's 2.9 mm diameter) or 6 mm outside it (wider).
  // Counted punctures outside the zone, by the same random numbers. The capsule meets the
  // real faces of skirt and flap (flight/face_touch.hpp): it cannot pass the 2-mm channel, so
  // that flap lets by what the flush one does (nails leaving under the skirt's foot, 6.4 mm
  // up), give or take the bounces the moved flap changes.
  std::ifstream in(scenario_path("highway-pivoted.toml"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto replace = [&](std::string& s, const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    REQUIRE(at != std::string::npos);
    s.replace(at, from.size(), to);
  };
  replace(text, "skirt_bottom = \"1.5 in\"", "skirt_bottom = \"0.25 in\"");
  replace(text, "skirt_depth = \"7 in\"", "skirt_depth = \"8.25 in\"");
  const auto with_flap = [&](double gap) {
    const double r = 24 * units::inch + 0.05 + gap;  // the deck's radius: the reach and its margin
    std::string along;
    for (int k = 0; k <= 10; ++k) {
      const double a = (155 + 5 * k) * units::degree;
      along += fmt::format("{}[\"{:.6f} m\", \"{:.6f} m\"]", k ? ", " : "", r * std::cos(a), r * std::sin(a));
    }
    std::string s = text;
    replace(s, "[housing]\n", fmt::format("[[housing.openings]]\nname = \"rear\"\nazimuth_from = \"160 deg\"\nazimuth_to = \"200 deg\"\n\n"
                                          "[[housing.guards]]\nname = \"flap\"\nalong = [{}]\ntop = \"8.5 in\"\nbottom = \"0.25 in\"\n"
                                          "openness = 0\nrestitution = 0.2\n\n[housing]\n",
                                          along));
    auto sc = read(s);
    sc.run.replicates = 150;
    // Closed all round 1/4 in above the turf, a nail may ride round the skirt for hundreds
    // of grazing bounces before it settles: the bounce limit is raised so that none is cut off.
    sc.run.max_bounces = 1000;
    return sc;
  };
  const auto punctures_outside = [](const scenario::Scenario& sc) {
    std::uint64_t n = 0;
    assess::run_assessment(assess::Simulator(sc), 2, nullptr, [&](const assess::MarkRow& r) {
      n += r.mark.counted && r.mark.puncture && !r.mark.in_zone;
    });
    return n;
  };
  const auto flush = punctures_outside(with_flap(0.0)), narrow = punctures_outside(with_flap(0.002)),
             gap = punctures_outside(with_flap(0.006));
  INFO("punctures outside the zone: " << flush << " with the flap flush, " << narrow << " with it 2 mm out, " << gap
                                      << " with it 6 mm out (of 22 500 nails)");
  const auto noise = [](std::uint64_t n) { return 3 * std::sqrt(static_cast<double>(n)) + 3; };
  CHECK(std::abs(static_cast<double>(narrow) - static_cast<double>(flush)) <= noise(flush));
  // (The 6-mm channel is wider than the nail and may let some by: 25 and 15 against the flush
  // flap's 5 and 9 in two versions of the search; at this sample that is within the noise, so
  // it is reported, not asserted.)
}

TEST_CASE("deck: an opening is cut exactly at its azimuths, and its width as cut is its stretch of the outline", "[deck][housing]") {
  auto s = scenario::read_scenario(scenario_path("deck-72in-three-spindle.toml"));
  REQUIRE(s.housing.openings.size() == 1);
  for (const double width_deg : {40.0, 23.0, 31.7}) {  // none a whole number of 0.1 m pieces
    auto& o = s.housing.openings[0];
    o.azimuth.from = -90 * units::degree - 0.5 * width_deg * units::degree;
    o.azimuth.to = -90 * units::degree + 0.5 * width_deg * units::degree;
    // The pieces inside the opening begin and end on its azimuths' rays.
    double from_gap = HUGE_VAL, to_gap = HUGE_VAL, inside = 0;
    for (const auto& piece : scene::skirt_pieces(s)) {
      from_gap = std::min({from_gap, std::abs(std::remainder(std::atan2(piece.a.y(), piece.a.x()) - o.azimuth.from, units::two_pi)),
                           std::abs(std::remainder(std::atan2(piece.b.y(), piece.b.x()) - o.azimuth.from, units::two_pi))});
      to_gap = std::min({to_gap, std::abs(std::remainder(std::atan2(piece.a.y(), piece.a.x()) - o.azimuth.to, units::two_pi)),
                         std::abs(std::remainder(std::atan2(piece.b.y(), piece.b.x()) - o.azimuth.to, units::two_pi))});
      const double rel = std::remainder(piece.azimuth - o.azimuth.from, units::two_pi);
      if (rel > 0 && rel < width_deg * units::degree) inside += (piece.b - piece.a).norm();
    }
    CHECK(from_gap < 1e-12);
    CHECK(to_gap < 1e-12);
    // The width as cut: the outline between the two rays, walked finely (independent of the pieces).
    double walked = 0;
    Eigen::Vector2d last;
    bool started = false;
    const auto pieces = scene::skirt_pieces(s);
    for (int i = 0; i <= 20000; ++i) {
      const double a = o.azimuth.from + (o.azimuth.to - o.azimuth.from) * i / 20000.0;
      // The outline's point on the ray at a: the farthest crossing of the ray with any piece.
      const Eigen::Vector2d d(std::cos(a), std::sin(a));
      double reach = 0;
      for (const auto& p : pieces) {
        const Eigen::Vector2d e = p.b - p.a;
        const double den = d.x() * e.y() - d.y() * e.x();
        if (std::abs(den) < 1e-15) continue;
        const double t = (p.a.x() * d.y() - p.a.y() * d.x()) / den;
        if (t < -1e-12 || t > 1 + 1e-12) continue;
        reach = std::max(reach, (p.a + t * e).dot(d));
      }
      const Eigen::Vector2d x = reach * d;
      if (started) walked += (x - last).norm();
      last = x, started = true;
    }
    const double cut = scene::opening_widths(s)[0];
    CHECK(cut == Approx(inside).epsilon(1e-12));
    CHECK(cut == Approx(walked).epsilon(1e-6));
  }
}

TEST_CASE("deck: a flap given by azimuths hangs across an opening to any height above the turf", "[deck][housing][input]") {
  using Catch::Contains;
  const std::string deck = kThree + R"(
[housing]
skirt_bottom = "1.5 in"
[[housing.openings]]
name = "rear"
azimuth_from = "160 deg"
azimuth_to = "200 deg"
top = "5 in"
)";
  // A flap across the opening, its lower edge 2.5 in above the turf (above the skirt's foot).
  const auto s = read(deck + "[[housing.guards]]\nname = \"flap\"\nazimuth_from = \"155 deg\"\nazimuth_to = \"205 deg\"\nbottom = \"2.5 in\"\n");
  const auto soup = scene::build_scene_soup(s);
  double lowest = HUGE_VAL, highest = 0, min_az = HUGE_VAL, max_az = -HUGE_VAL;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (soup.labels[t] == scene::Surface::Guard)
      for (auto v : soup.triangles[t]) {
        const auto& p = soup.points[v];
        lowest = std::min(lowest, p.z()), highest = std::max(highest, p.z());
        const double az = std::fmod(std::atan2(p.y(), p.x()) / units::degree + 360, 360);
        min_az = std::min(min_az, az), max_az = std::max(max_az, az);
      }
  CHECK(lowest == Approx(2.5 * 0.0254));
  CHECK(highest == Approx(5 * 0.0254));
  CHECK(min_az == Approx(160).margin(1e-9));  // only across the opening: the skirt stands beside it
  CHECK(max_az == Approx(200).margin(1e-9));
  // Above the skirt's foot and spanning no opening (or above the opening's top), it would hang nowhere.
  CHECK_THROWS_WITH(read(deck + "[[housing.guards]]\nazimuth_from = \"10 deg\"\nazimuth_to = \"50 deg\"\nbottom = \"2.5 in\"\n"),
                    Contains("housing.guards[1].bottom") && Contains("would hang nowhere"));
  CHECK_THROWS_WITH(read(deck + "[[housing.guards]]\nazimuth_from = \"150 deg\"\nazimuth_to = \"210 deg\"\nbottom = \"5.5 in\"\n"),
                    Contains("would hang nowhere"));
}

TEST_CASE("deck: deck_top holds the plate where it is while the skirt's foot moves", "[deck][housing][input]") {
  using Catch::Contains;
  const auto with = [&](const std::string& housing) { return read(kThree + "[housing]\n" + housing); };
  const auto low = with("skirt_bottom = \"1 in\"\ndeck_top = \"6 in\"\n"), high = with("skirt_bottom = \"3 in\"\ndeck_top = \"6 in\"\n");
  CHECK(low.housing.skirt_bottom + low.housing.skirt_depth == Approx(6 * 0.0254));
  CHECK(high.housing.skirt_bottom + high.housing.skirt_depth == Approx(6 * 0.0254));
  CHECK(high.housing.skirt_depth == Approx(3 * 0.0254));
  CHECK_THROWS_WITH(with("deck_top = \"6 in\"\nskirt_depth = \"4 in\"\n"), Contains("housing.deck_top") && Contains("not both"));
  CHECK_THROWS_WITH(with("skirt_bottom = \"7 in\"\ndeck_top = \"6 in\"\n"), Contains("housing.deck_top") && Contains("above the skirt's bottom"));
}

TEST_CASE("target: a board of shape outline stands its distance outside every tip circle", "[deck][housing][input]") {
  using Catch::Contains;
  auto s = read(kThree + "[target]\nshape = \"outline\"\ndistance = \"0.5 m\"\n");
  REQUIRE(s.target.shape == scenario::TargetSpec::Shape::Outline);
  const auto soup = scene::build_scene_soup(s);
  std::vector<double> nearest(s.spindles.size(), HUGE_VAL);
  std::size_t board = 0;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (scene::is_target(soup.labels[t]))
      for (auto v : soup.triangles[t]) {
        ++board;
        const auto& p = soup.points[v];
        for (std::size_t k = 0; k < s.spindles.size(); ++k) {
          const double d = std::hypot(p.x() - s.spindles[k].x, p.y() - s.spindles[k].y) - s.spindles[k].blade.tip_radius();
          nearest[k] = std::min(nearest[k], d);
          CHECK(d >= 0.5 * std::cos(units::pi / 96) - 0.02);  // never nearer than the distance (a polygon's side aside)
        }
      }
  REQUIRE(board > 100);
  for (const double d : nearest) CHECK(d == Approx(0.5).margin(0.005));  // it follows every tip circle at the distance
  // A ring about the centre stands that far outside the farthest tip only.
  const auto ring = read(kThree + "[target]\ndistance = \"0.5 m\"\n");
  CHECK(scene::target_radius(ring) == Approx(ring.reach() + 0.5));
  CHECK(scene::target_radius(s) < ring.reach() + 0.5 + 1e-9);
  CHECK_THROWS_WITH(read(kThree + "[target]\nshape = \"square\"\n"), Contains("target.shape") && Contains("outline"));
}

TEST_CASE("flap: a belting flap across the discharge turns nails back; none passes through it", "[deck][housing]") {
  auto s = scenario::read_scenario(scenario_path("deck-72in-discharge-flap.toml"));
  REQUIRE(s.housing.guards.size() == 1);
  const auto& flap = s.housing.guards[0];
  REQUIRE(flap.kind == scenario::GuardSpec::Kind::Flap);
  const auto f = scene::flap_geometry(s, flap);
  CHECK(f.hinge == Approx(6.5 * 0.0254));  // hung from the opening's top
  CHECK(f.width == Approx(scene::opening_widths(s)[0]));
  const assess::Simulator sim(s);
  int flap_hits = 0, through_opening = 0;
  for (std::uint64_t r = 0; r < 10; ++r)
    for (int n = 0; n < s.feed.nails; ++n) {
      const auto o = sim.simulate(r, n);
      const auto& t = o.flight.trace;
      for (int i = 0; i < std::min(t.touch_count, flight::NailTrace::kMaxTouches); ++i) {
        CHECK(t.touches[static_cast<std::size_t>(i)] != flight::Touch::GuardPass);  // a solid plate
        flap_hits += t.touches[static_cast<std::size_t>(i)] == flight::Touch::GuardBounce;
      }
      if (t.exit == flight::Exit::Opening) {
        ++through_opening;
        // Only under the flap: the centre within the nail's reach of its lower edge.
        CHECK(t.exit_height < flap.bottom + 0.5 * s.nail.length + s.nail.diameter);
      }
    }
  CHECK(flap_hits > 100);
  CHECK(through_opening > 0);
}

TEST_CASE("estimates: inputs the author marks as estimates are listed among the assumptions as written", "[deck][input]") {
  using Catch::Contains;
  const auto s = read("estimates = [\"housing.skirt_bottom\", \"blades.bar.speed\"]\n" + kThree + "[housing]\nskirt_bottom = \"1.5 in\"\n");
  REQUIRE(s.estimates.size() == 2);
  const auto listed = report::assumptions(s);
  const auto has = [&](const std::string& what) {
    return std::any_of(listed.begin(), listed.end(), [&](const report::Assumption& a) { return a.what == what && a.source.find("estimate") != std::string::npos; });
  };
  CHECK(has("housing.skirt_bottom = 1.5 in"));
  CHECK(has("blades.bar.speed = 2700 rpm"));
  // A key naming no value (a misspelling, a table, an array of tables) is refused.
  CHECK_THROWS_WITH(read("estimates = [\"housing.skirt_botom\"]\n" + kThree + "[housing]\nskirt_bottom = \"1.5 in\"\n"),
                    Contains("estimates") && Contains("housing.skirt_botom") && Contains("names no value"));
  CHECK_THROWS_WITH(read("estimates = [\"spindles\"]\n" + kThree), Contains("names no value"));
  CHECK_THROWS_WITH(read("estimates = \"housing\"\n" + kThree), Contains("array of"));
}

TEST_CASE("deck: no nail passes through the skirt: every way out within its height is an opening's", "[deck][housing]") {
  // A capsule end that crossed a wall in one chord used to be found only in the next, deep in
  // it, and the rebound could leave the centre going on through (80 of 3000 nails of this deck
  // crossed its outline within the skirt's height outside the opening). The centre's ray now
  // looks ahead of its chord by four of the nail's reaches.
  auto s = scenario::read_scenario(scenario_path("deck-72in-three-spindle.toml"));
  const assess::Simulator sim(s);
  const auto& o = s.housing.openings.at(0);
  int through_skirt = 0, left = 0;
  for (std::uint64_t r = 0; r < 10; ++r)
    for (int n = 0; n < s.feed.nails; ++n) {
      const auto& t = sim.simulate(r, n).flight.trace;
      if (t.first_exit == flight::Exit::Inside) continue;
      ++left;
      if (t.exit != flight::Exit::Opening) continue;
      const double rel = std::fmod(std::fmod(t.exit_azimuth - o.azimuth.from, units::two_pi) + units::two_pi, units::two_pi);
      const bool through = rel > std::fmod(o.azimuth.to - o.azimuth.from + units::two_pi, units::two_pi) + 1e-9;
      if (through) UNSCOPED_INFO("replicate " << r << " nail " << n << " left at azimuth " << t.exit_azimuth << ", height " << t.exit_height);
      through_skirt += through;
    }
  CHECK(through_skirt == 0);
  CHECK(left > 1000);
}

TEST_CASE("deck: a guard described but not fitted (present = false) is checked, named, and not built", "[deck][housing][guards]") {
  toml::table doc = scenario::parse_toml_file(scenario_path("highway-pivoted-chains.toml"));
  scenario::set_key(doc, "housing.guards.present", "false", "test");
  const auto without = scenario::read_scenario(doc, "chains-absent.toml");
  CHECK(without.housing.guards.empty());
  REQUIRE(without.housing.absent_guards.size() == 2);
  CHECK(without.housing.absent_guards[0] == "front chains");
  // The same mower as the one shipped without guards, nail for nail.
  auto plain = scenario::read_scenario(scenario_path("highway-pivoted.toml"));
  auto absent = without;
  plain.run.replicates = absent.run.replicates = 20;
  const auto a = assess::run_assessment(assess::Simulator(plain), 2), b = assess::run_assessment(assess::Simulator(absent), 2);
  CHECK(a.passed == b.passed);
  CHECK(a.marks == b.marks);
  CHECK(a.fates == b.fates);
  // ...and the report says so.
  bool named = false;
  for (const auto& x : report::assumptions(without)) named = named || x.what.find("'front chains' is described but not fitted") != std::string::npos;
  CHECK(named);
  // A bad guard is refused even when it is not fitted.
  scenario::set_key(doc, "housing.guards.openness", "2", "test");
  CHECK_THROWS_AS(scenario::read_scenario(doc, "chains-absent.toml"), scenario::InputError);
}

// The shipped discharge-flap deck with its flap's restitution 0 (allowed: a dead rubber flap).
std::string flap_deck_at_restitution_zero() {
  std::ifstream in(scenario_path("deck-72in-discharge-flap.toml"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "restitution = 0.3 ";
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), "restitution = 0.0 ");
}

TEST_CASE("deck: a flap with restitution 0 runs to a verdict, none cut off by the bounce cap", "[deck][housing][long]") {
  // Issue 31's trap: a flap at e = 0 was touched again at the same instant hundreds of times
  // (11 % of the shipped flap deck's nails cut off by max_bounces). Its nails now slide under
  // the flap's foot by gentle contacts (slower than sqrt(2 g D)), counted apart from bounces;
  // a nail pinched between a knife and a face is named as wedged, not as a bounce cap.
  const std::string text = flap_deck_at_restitution_zero();
  auto sc = read(text);
  sc.run.replicates = 40;
  const assess::Assessment a = assess::run_assessment(assess::Simulator(sc), 2);
  const auto by = [&](flight::CutOff c) { return a.cut_off_by.counts.at(static_cast<std::size_t>(c)); };
  std::uint64_t cut = 0;
  for (auto n : a.cut_off_by.counts) cut += n;
  INFO("cut off: " << cut << " of " << 40 * 150 << " (wedged " << by(flight::CutOff::Wedged) << ")");
  CHECK(by(flight::CutOff::MaxBounces) == 0);
  CHECK(by(flight::CutOff::MaxGentleContacts) == 0);
  CHECK(cut <= 6);  // 0.1 %: the run is valid (was 7.3 % cut off)
}

TEST_CASE("deck: a nail pressed along a flap at restitution 0 is not stepped by nanoseconds into the gentle-contact cap", "[deck][housing][long]") {
  // A nail sliding on under a flap at e = 0, sunk within a nanometre of the 10 um a face being
  // left may be entered (flight/face_touch.hpp), got a bound of a few nanoseconds on what was
  // left, which was not renewed (only a bound of exactly zero was): the search stepped a few
  // nanoseconds at a time, each step ending in a gentle contact with no rebound, 100 000 of
  // them, and the nail was cut off. At these seeds the build before the fix cut off 2, 1 and 1
  // of the 15 000 nails (seeds 4, 8, 10); this build with only the renewal's condition put back
  // (`!(safe > 0)`) cuts off one at seed 10. (tests/test_face_touch.cpp sets the state up directly.)
  const std::string text = flap_deck_at_restitution_zero();
  for (const std::uint64_t seed : {4u, 8u, 10u}) {
    auto sc = read(text);
    sc.run.replicates = 100;
    sc.run.seed = seed;
    const assess::Assessment a = assess::run_assessment(assess::Simulator(sc), 2);
    INFO("seed " << seed);
    CHECK(a.cut_off_by.counts.at(static_cast<std::size_t>(flight::CutOff::MaxGentleContacts)) == 0);
    CHECK(a.cut_off_by.counts.at(static_cast<std::size_t>(flight::CutOff::MaxBounces)) == 0);
    // Pressed on under the flap, a rare nail sinks on by renewed slacks; past kDeepestSink it is
    // cut off, named (at seed 10, one: 0.13 mm into the flap before the cap, beyond the 0.1 mm the
    // audit allows). Never more than a few in 15 000.
    CHECK(a.cut_off_by.counts.at(static_cast<std::size_t>(flight::CutOff::SankIntoFace)) <= 2);
  }
}
