#include "report/board_views.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <set>
#include <stdexcept>

#include "flight/deck_outline.hpp"
#include "report/html_page.hpp"
#include "report/svg_chart.hpp"
#include "scene/j232_setup.hpp"
#include "units/quantity.hpp"

namespace j232::report {

namespace {

using json = nlohmann::ordered_json;

const std::string kHitColour = "#0072B2", kPunctureColour = "#D55E00", kZoneColour = "#E69F00", kBoardColour = "#8a8a8a",
                  kUncountedColour = "#b8b8b8";

// ---------------------------------------------------------------------------------------
// What the pictures need of the run and its scene, into result.json's "pictures".

// The board unrolled onto a grid of 1 deg x 1 cm cells; each cell says whether a target
// triangle (and which label) covers its centre. Kept and drawn as runs of equal cells along
// a row: a few hundred rectangles instead of thousands of triangles.
struct BoardRaster {
  static constexpr int kCols = 360;
  static constexpr double kCell = 0.01;  // m
  double z0 = 0;
  int rows = 0;
  std::vector<std::uint8_t> cell;  // 0 none, 1 board outside the zone, 2 operator zone

  explicit BoardRaster(const scene::Soup& soup) {
    double lo = 1e300, hi = -1e300;
    for (std::size_t t = 0; t < soup.triangles.size(); ++t)
      if (scene::is_target(soup.labels[t]))
        for (auto v : soup.triangles[t]) lo = std::min(lo, soup.points[v].z()), hi = std::max(hi, soup.points[v].z());
    if (!(hi > lo)) return;
    z0 = lo;
    rows = static_cast<int>(std::min(2000.0, std::ceil((hi - lo) / kCell)));  // clamped before the cast: no overflow
    cell.assign(static_cast<std::size_t>(rows) * kCols, 0);
    for (std::size_t t = 0; t < soup.triangles.size(); ++t)
      if (scene::is_target(soup.labels[t])) paint(soup, t, soup.labels[t] == scene::Surface::TargetZone ? 2 : 1);
  }

  void paint(const scene::Soup& soup, std::size_t t, std::uint8_t value) {
    std::array<double, 3> a{}, z{};
    for (int k = 0; k < 3; ++k) {
      const auto& p = soup.points[soup.triangles[t][k]];
      a[k] = azimuth_deg(p.x(), p.y());
      z[k] = p.z();
      if (k > 0) a[k] = a[0] + std::remainder(a[k] - a[0], 360.0);  // unwrap across +/-180
    }
    const double area = (a[1] - a[0]) * (z[2] - z[0]) - (a[2] - a[0]) * (z[1] - z[0]);
    if (std::abs(area) < 1e-12) return;  // seen edge-on
    const int c0 = static_cast<int>(std::floor(*std::min_element(a.begin(), a.end()) + 180.0));
    const int c1 = static_cast<int>(std::ceil(*std::max_element(a.begin(), a.end()) + 180.0));
    // Rows are clamped in floating point before the cast, so a huge mesh cannot overflow an int.
    const auto row = [&](double v) { return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(rows))); };
    const int r0 = row(std::floor((*std::min_element(z.begin(), z.end()) - z0) / kCell));
    const int r1 = row(std::ceil((*std::max_element(z.begin(), z.end()) - z0) / kCell));
    for (int c = c0; c < c1; ++c)
      for (int r = r0; r < r1; ++r) {
        const double pa = c - 180.0 + 0.5, pz = z0 + (r + 0.5) * kCell;
        // Barycentric sign test.
        const auto side = [&](int i, int j) { return (a[j] - a[i]) * (pz - z[i]) - (z[j] - z[i]) * (pa - a[i]); };
        const double s0 = side(0, 1), s1 = side(1, 2), s2 = side(2, 0);
        if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) {
          auto& v = cell[static_cast<std::size_t>(r) * kCols + static_cast<std::size_t>(((c % kCols) + kCols) % kCols)];
          v = std::max(v, value);
        }
      }
  }

  // Runs of covered cells along each row, in row order: [row, first column, end column,
  // 1 for the board outside the zone or 2 for the operator zone].
  json runs() const {
    json out = json::array();
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < kCols;) {
        const std::uint8_t v = cell[static_cast<std::size_t>(r) * kCols + c];
        int e = c + 1;
        while (e < kCols && cell[static_cast<std::size_t>(r) * kCols + e] == v) ++e;
        if (v != 0) out.push_back({r, c, e, v});
        c = e;
      }
    return out;
  }
};

// The marks of the first replicates: the runner kept those of its first replicates; as
// many whole replicates of those as fit in `max_marks` (at least one), as columns.
json mark_sample_json(const assess::Assessment& a, std::size_t max_marks) {
  const auto& kept = a.mark_sample;
  std::size_t end = 0;
  std::uint64_t shown = 0;
  while (shown < a.mark_sample_replicates) {
    std::size_t next = end;
    while (next < kept.size() && kept[next].replicate == shown) ++next;
    if (shown > 0 && next > max_marks) break;
    end = next;
    ++shown;
  }
  std::vector<double> x, y, z;
  std::string kind;  // per mark: h a counted hit, p a counted puncture, u a mark below the counted height
  for (std::size_t i = 0; i < end; ++i) {
    const auto& m = kept[i].mark;
    x.push_back(m.point.x()), y.push_back(m.point.y()), z.push_back(m.point.z());
    kind += !m.counted ? 'u' : m.puncture ? 'p' : 'h';
  }
  return {{"replicates_shown", shown},
          {"replicates", a.replicates},
          {"located_marks", a.marks + a.uncounted_marks - a.unlocated_marks},
          {"kind", kind},
          {"x_m", x},
          {"y_m", y},
          {"z_m", z}};
}

// The plan view's layers, one per kind of surface seen from above (and one more for flaps,
// guards of kind "flap", drawn apart from chain curtains; the ground is not drawn). Vertical
// faces project to segments (deduplicated to 1 mm), others to filled triangles.
struct PlanLayer {
  const char* name;
  const char* label;
  std::string colour;
  double width;
};
const std::array<PlanLayer, 6>& plan_layers() {
  static const std::array<PlanLayer, 6> layers = {PlanLayer{"housing", "housing (deck, skirt)", "#555555", 1.2},
                                                  PlanLayer{"deflector", "deflector", "#009E73", 2.0},
                                                  PlanLayer{"chain_guard", "chain guard", "#CC79A7", 2.5},
                                                  PlanLayer{"flap", "flap (belting)", "#222222", 4.0},
                                                  PlanLayer{"target_board", "target board", kBoardColour, 2.0},
                                                  PlanLayer{"operator_zone_board", "operator zone board", kZoneColour, 3.0}};
  return layers;
}
// The plan layer of a scene triangle (-1: none drawn).
int plan_layer_of(scene::Surface kind, bool flap) {
  switch (kind) {
    case scene::Surface::Housing: return 0;
    case scene::Surface::Deflector: return 1;
    case scene::Surface::Guard: return flap ? 3 : 2;
    case scene::Surface::TargetOutside: return 4;
    case scene::Surface::TargetZone: return 5;
    default: return -1;
  }
}

json plan_json(const scenario::Scenario& s, const scene::Soup& soup) {
  struct Layer {
    std::vector<double> triangles, segments;  // x, y of each corner; x0, y0, x1, y1 of each segment
    std::set<std::array<long long, 4>> seen;
  };
  std::array<Layer, 6> layers;
  const std::vector<scenario::GuardSpec> guards = scene::scene_guards(s);
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    const auto kind = soup.labels[t];
    const bool flap = kind == scene::Surface::Guard && soup.guard_index[t] < guards.size() &&
                      guards[soup.guard_index[t]].kind == scenario::GuardSpec::Kind::Flap;
    const int index = plan_layer_of(kind, flap);
    if (index < 0) continue;
    Layer& layer = layers[static_cast<std::size_t>(index)];
    const auto& p0 = soup.points[soup.triangles[t][0]];
    const auto& p1 = soup.points[soup.triangles[t][1]];
    const auto& p2 = soup.points[soup.triangles[t][2]];
    const double area = (p1.x() - p0.x()) * (p2.y() - p0.y()) - (p2.x() - p0.x()) * (p1.y() - p0.y());
    const double size = std::max({(p1 - p0).head<2>().squaredNorm(), (p2 - p0).head<2>().squaredNorm(), (p2 - p1).head<2>().squaredNorm()});
    if (std::abs(area) > 1e-3 * size) {
      for (const auto* p : {&p0, &p1, &p2}) layer.triangles.push_back(p->x()), layer.triangles.push_back(p->y());
      continue;
    }
    // The longest projected edge.
    std::array<const scene::Vec3*, 3> v{&p0, &p1, &p2};
    std::pair<int, int> best{0, 1};
    double longest = -1;
    for (auto [i, j] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{0, 2}}) {
      const double d = (v[i]->head<2>() - v[j]->head<2>()).squaredNorm();
      if (d > longest) longest = d, best = {i, j};
    }
    auto q = [](double c) { return std::llround(c * 1000); };
    std::array<long long, 4> key{q(v[best.first]->x()), q(v[best.first]->y()), q(v[best.second]->x()), q(v[best.second]->y())};
    if (std::make_pair(key[2], key[3]) < std::make_pair(key[0], key[1])) std::swap(key[0], key[2]), std::swap(key[1], key[3]);
    if (!layer.seen.insert(key).second) continue;
    for (const double c : {v[best.first]->x(), v[best.first]->y(), v[best.second]->x(), v[best.second]->y()}) layer.segments.push_back(c);
  }
  json out = json::array();
  for (std::size_t k = 0; k < layers.size(); ++k)
    if (!layers[k].triangles.empty() || !layers[k].segments.empty())
      out.push_back({{"layer", plan_layers()[k].name}, {"triangles_xy_m", layers[k].triangles}, {"segments_xy_m", layers[k].segments}});
  return out;
}

bool scene_has_target_mesh(const scenario::Scenario& s) {
  for (const auto& m : s.meshes)
    if (scenario::is_board(m.label)) return true;
  return false;
}

// The board in the side elevation: its distance from the deck's centre (a ring's one, or a
// board along the deck's nearest and farthest), its bottom and top; null for a board from a mesh.
json board_side_json(const scenario::Scenario& s) {
  if (scene_has_target_mesh(s)) return nullptr;
  std::vector<double> distances;
  if (s.target.shape == scenario::TargetSpec::Shape::Circle) {
    distances = {s.reach() + s.target.distance};
  } else {  // a board along the deck stands at a range of distances from the centre
    double nearest = HUGE_VAL, farthest = 0;
    const auto outline = scene::board_outline(s);
    for (const auto& p : outline) farthest = std::max(farthest, p.norm());
    for (std::size_t i = 0; i < outline.size(); ++i) {  // nearest: to each side, not only to the corners
      const Eigen::Vector2d &a = outline[i], &b = outline[(i + 1) % outline.size()], d = b - a;
      const double t = std::clamp(-a.dot(d) / std::max(d.squaredNorm(), 1e-18), 0.0, 1.0);
      nearest = std::min(nearest, (a + t * d).norm());
    }
    distances = {nearest, farthest};
  }
  return {{"distances_m", distances}, {"bottom_m", s.target.bottom}, {"top_m", s.target_top()}};
}

// ---------------------------------------------------------------------------------------
// The pictures, from result.json as saved.

std::vector<double> numbers(const json& j) { return j.get<std::vector<double>>(); }
// A flat list of coordinates in groups of `group` (x, y of a corner; x0, y0, x1, y1 of a segment).
std::vector<double> grouped(const json& j, std::size_t group, const char* what) {
  std::vector<double> v = numbers(j);
  if (v.size() % group != 0) throw std::out_of_range(fmt::format("{}: {} numbers, expected a multiple of {}", what, v.size(), group));
  return v;
}

void draw_board(Chart& chart, const json& board) {
  const double z0 = board.at("from_height_m").get<double>(), cell = board.at("cell_height_m").get<double>();
  bool labelled[3] = {false, false, false};
  for (const auto& run : board.at("runs")) {
    const char* what = "pictures.board_unrolled.runs";
    if (run.size() != 4) throw std::out_of_range(fmt::format("{}: expected [row, first column, end column, kind], not {}", what, run.size()));
    const int r = static_cast<int>(whole(run.at(0), what, 0, 100000)), c = static_cast<int>(whole(run.at(1), what, 0, BoardRaster::kCols - 1)),
              e = static_cast<int>(whole(run.at(2), what, c + 1, BoardRaster::kCols));
    const auto v = static_cast<std::size_t>(whole(run.at(3), what, 1, 2));
    const bool zone = v == 2;
    const std::string label = labelled[v] ? "" : (zone ? "operator zone" : "target board");
    labelled[v] = true;
    chart.rect(c - 180.0, z0 + r * cell, e - 180.0, z0 + (r + 1) * cell, zone ? kZoneColour : kBoardColour, zone ? 0.45 : 0.18, label);
  }
}

void draw_marks(Chart& chart, const json& marks, bool plan) {
  const std::string kind = marks.at("kind").get<std::string>();
  const std::vector<double> mx = numbers(marks.at("x_m")), my = numbers(marks.at("y_m")), mz = numbers(marks.at("z_m"));
  if (mx.size() != kind.size() || my.size() != kind.size() || mz.size() != kind.size())
    throw std::out_of_range(fmt::format("pictures.marks: x_m, y_m and z_m hold {}, {} and {} values for {} marks of kind", mx.size(),
                                        my.size(), mz.size(), kind.size()));
  std::vector<double> hx, hy, px, py, ux, uy;
  for (std::size_t i = 0; i < kind.size(); ++i) {
    if (kind[i] != 'h' && kind[i] != 'p' && kind[i] != 'u')
      throw std::out_of_range(fmt::format("pictures.marks.kind: expected h, p or u for each mark, not '{}'", kind[i]));
    const double x = plan ? mx[i] : azimuth_deg(mx[i], my[i]);
    const double y = plan ? my[i] : mz[i];
    std::vector<double>* xs = kind[i] == 'u' ? &ux : kind[i] == 'p' ? &px : &hx;
    std::vector<double>* ys = kind[i] == 'u' ? &uy : kind[i] == 'p' ? &py : &hy;
    xs->push_back(x), ys->push_back(y);
  }
  if (!ux.empty()) chart.points(ux, uy, kUncountedColour, fmt::format("not counted ({})", ux.size()), 1.6);
  chart.points(hx, hy, kHitColour, fmt::format("hit ({})", hx.size()), 1.8);
  chart.points(px, py, kPunctureColour, fmt::format("puncture ({})", px.size()), 2.6);
}

std::string sample_caption(const json& m) {
  const auto shown = count_of(m.at("replicates_shown"), "pictures.marks.replicates_shown"),
             replicates = count_of(m.at("replicates"), "pictures.marks.replicates");
  const auto located = count_of(m.at("located_marks"), "pictures.marks.located_marks");
  if (shown == replicates) return fmt::format("All {} located marks of {} replicates.", located, replicates);
  return fmt::format("Marks of the first {} of {} replicates ({} of {} located marks): a fair sample, replicates are independent.", shown,
                     replicates, m.at("kind").get<std::string>().size(), located);
}

// The mower, guards, board, tip circles, feed stations and seat seen from above.
void draw_mower_plan(Chart& chart, const json& pictures) {
  chart.equal_aspect();
  const json& plan = pictures.at("plan");
  for (const PlanLayer& style : plan_layers()) {
    const auto it = std::find_if(plan.at("layers").begin(), plan.at("layers").end(), [&](const json& l) { return l.at("layer") == style.name; });
    if (it == plan.at("layers").end()) continue;
    const std::vector<double> t = grouped((*it).at("triangles_xy_m"), 6, "pictures.plan.layers' triangles_xy_m"),
                              s = grouped((*it).at("segments_xy_m"), 4, "pictures.plan.layers' segments_xy_m");
    std::vector<double> tx, ty, x0, y0, x1, y1;
    for (std::size_t i = 0; i + 1 < t.size(); i += 2) tx.push_back(t[i]), ty.push_back(t[i + 1]);
    for (std::size_t i = 0; i + 3 < s.size(); i += 4) x0.push_back(s[i]), y0.push_back(s[i + 1]), x1.push_back(s[i + 2]), y1.push_back(s[i + 3]);
    if (!tx.empty()) chart.triangles(tx, ty, style.colour, 0.12, x0.empty() ? style.label : "");
    if (!x0.empty()) chart.segments(x0, y0, x1, y1, style.colour, style.label, style.width);
  }
  const json& circles = plan.at("tip_circles");
  for (std::size_t k = 0; k < circles.size(); ++k) {
    const double r = circles[k].at("radius_m").get<double>();
    chart.circle(circles[k].at("x_m").get<double>(), circles[k].at("y_m").get<double>(), r, "#000",
                 k == 0 ? fmt::format("blade tip circle{} (r {:.3f} m)", circles.size() > 1 ? "s" : "", r) : "", true);
  }
  std::vector<double> fx, fy;
  for (const auto& f : pictures.at("feed_stations")) fx.push_back(f.at("x_m").get<double>()), fy.push_back(f.at("y_m").get<double>());
  chart.points(fx, fy, "#009E73", "feed station", 4);
  if (!plan.at("operator_seat").is_null())
    chart.points({plan.at("operator_seat").at("x_m").get<double>()}, {plan.at("operator_seat").at("y_m").get<double>()}, "#000000", "operator seat", 4);
}

std::string path_colour(const std::string& why) {
  const auto c = path_rgb(why);
  return fmt::format("#{:02X}{:02X}{:02X}", c[0], c[1], c[2]);
}

// The plan view draws at most this many paths of each kind: more make a blot inside the deck.
constexpr std::size_t kPlanPathsPerKind = 20;
// The most corners of a deck's outline a saved file may give (a generated deck has 96).
constexpr std::size_t kMostOutlineCorners = 4096;

std::string paths_caption(const json& trajectories) {
  std::size_t n[3] = {0, 0, 0};
  for (const auto& t : trajectories.at("paths")) ++n[t.at("why") == "sample" ? 0 : t.at("why") == "operator zone" ? 1 : 2];
  const auto not_kept = count_of(trajectories.at("notable_not_kept"), "trajectories.notable_not_kept");
  return fmt::format(
      "{} sampled nails (the first struck in replicate 0), {} that marked the operator zone and {} that punctured the "
      "board elsewhere{}.",
      n[0], n[1], n[2],
      not_kept ? fmt::format(" (at most 100 of each, chosen at random from the whole run; {} more not drawn)", not_kept) : std::string());
}

}  // namespace

double azimuth_deg(double x, double y) { return std::atan2(y, x) / units::degree; }

json pictures_json(const scenario::Scenario& s, const assess::Assessment& a, const scene::Soup& soup) {
  const BoardRaster raster(soup);
  json stations = json::array();
  for (const auto& f : s.feed_stations()) stations.push_back({{"x_m", s.station_x(f)}, {"y_m", s.station_y(f)}});
  json circles = json::array();
  for (const auto& sp : s.spindles) circles.push_back({{"x_m", sp.x}, {"y_m", sp.y}, {"radius_m", sp.blade.tip_radius()}});
  const bool seat = s.zone.kind == scenario::OperatorZoneSpec::Kind::Derived;
  std::vector<double> outline;
  for (const auto& v : scene::deck_footprint(s, soup).outline) outline.push_back(v.x()), outline.push_back(v.y());
  return {
      {"note",
       "what the report's pictures draw that the rest of this file does not hold, so that j232 redraw can draw report.html again "
       "from this file alone"},
      {"blade_plane_m", s.blade_plane()},
      {"counted_height_m", s.criteria.counted_height ? json(s.counted_height()) : json(nullptr)},
      {"feed_stations", stations},
      {"board_unrolled",
       {{"note", "the target board's cells of 1 deg azimuth by 1 cm height, as runs along a row: [row, first column, end column, "
                 "1 board or 2 operator zone]; column c spans azimuth c - 180 to c - 179 deg"},
        {"from_height_m", raster.z0},
        {"cell_height_m", BoardRaster::kCell},
        {"runs", raster.runs()}}},
      {"marks", mark_sample_json(a, assess::kMarkSample)},
      {"plan",
       {{"layers", plan_json(s, soup)},
        {"tip_circles", circles},
        {"operator_seat", seat ? json{{"x_m", s.zone.seat_x}, {"y_m", s.zone.seat_y}} : json(nullptr)}}},
      {"deck_outline_xy_m", outline},
      {"board_side", board_side_json(s)},
  };
}

std::string hit_map_svg(const json& result) {
  const json& p = result.at("pictures");
  Chart chart("Hit map: the target board unrolled", "azimuth from straight ahead, counter-clockwise seen from above (deg)",
              "height above ground (m)", 900, 380);
  draw_board(chart, p.at("board_unrolled"));
  draw_marks(chart, p.at("marks"), false);
  const double blade_plane = p.at("blade_plane_m").get<double>();
  chart.hline(blade_plane, "#000", fmt::format("blade plane ({:.0f} mm)", 1000 * blade_plane));
  if (!p.at("counted_height_m").is_null()) {
    const double counted = p.at("counted_height_m").get<double>();
    chart.hline(counted, "#444", fmt::format("counted from {:.0f} mm (departs from J232)", 1000 * counted));
  }
  const json& stations = p.at("feed_stations");
  for (std::size_t i = 0; i < stations.size(); ++i)
    chart.vline(azimuth_deg(stations[i].at("x_m").get<double>(), stations[i].at("y_m").get<double>()), "#009E73",
                stations.size() > 1 ? fmt::format("feed {}", i + 1) : "feed station");
  chart.x_range(-180, 180);
  chart.x_ticks({-180, -135, -90, -45, 0, 45, 90, 135, 180});
  chart.caption(sample_caption(p.at("marks")));
  return chart.svg();
}

std::array<std::uint8_t, 3> path_rgb(const std::string& why) {
  if (why == "operator zone") return {0xE6, 0x9F, 0x00};  // kZoneColour
  if (why == "puncture") return {0xD5, 0x5E, 0x00};       // kPunctureColour
  return {0x00, 0x72, 0xB2};                              // kHitColour
}

std::string plan_view_svg(const json& result) {
  const json& p = result.at("pictures");
  Chart chart("Plan view: mower, guards, targets and marks", "x, forward (m)", "y, left (m)", 620, 600);
  draw_mower_plan(chart, p);
  draw_marks(chart, p.at("marks"), true);
  chart.caption(sample_caption(p.at("marks")));
  return chart.svg();
}

std::string trajectories_plan_svg(const json& result) {
  const json& p = result.at("pictures");
  const json& trajectories = result.at("trajectories");
  Chart chart("Paths of chosen nails, seen from above", "x, forward (m)", "y, left (m)", 620, 600);
  draw_mower_plan(chart, p);
  // A nail rattles inside the deck before it leaves: that part of each path is drawn faint,
  // and from the last point inside the deck's outline on, bold, so that where nails go
  // out and what they reach can be read.
  std::vector<Eigen::Vector2d> corners;
  const std::vector<double> outline = grouped(p.at("deck_outline_xy_m"), 2, "pictures.deck_outline_xy_m");
  // (A deck's outline has tens of corners: a file's thousands would make each point's test slow.)
  if (outline.size() > 2 * kMostOutlineCorners)
    throw std::out_of_range(fmt::format("pictures.deck_outline_xy_m: {} corners, at most {}", outline.size() / 2, kMostOutlineCorners));
  for (std::size_t i = 0; i + 1 < outline.size(); i += 2) corners.emplace_back(outline[i], outline[i + 1]);
  const flight::DeckOutline deck(corners);
  std::set<std::string> labelled;
  std::map<std::string, std::size_t> drawn;
  std::size_t left_out = 0;
  for (const auto& t : trajectories.at("paths")) {
    const std::string why = t.at("why").get<std::string>();
    if (++drawn[why] > kPlanPathsPerKind) {
      ++left_out;
      continue;
    }
    const json& points = t.at("points_m");
    std::size_t last_inside = 0;
    bool inside_ever = false;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (!deck.empty() && deck.contains(points[i].at(0).get<double>(), points[i].at(1).get<double>())) last_inside = i, inside_ever = true;
    std::vector<double> x, y, ox, oy;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double px = points[i].at(0).get<double>(), py = points[i].at(1).get<double>();
      if (inside_ever && i <= last_inside) x.push_back(px), y.push_back(py);
      if (!inside_ever || i >= last_inside) ox.push_back(px), oy.push_back(py);
    }
    const std::string colour = path_colour(why);
    if (x.size() > 1) chart.polyline(x, y, colour, "", 0.6, 0.18);
    if (ox.size() > 1) chart.polyline(ox, oy, colour, labelled.insert(why).second ? "path: " + why : "", 1.2, 0.75);
  }
  chart.caption(paths_caption(trajectories) +
                (deck.empty() ? std::string() : " Inside the deck's outline a path is drawn faint; from where it last left the deck, bold.") +
                (left_out ? fmt::format(" Here at most {} of each kind ({} more in the side elevation).", kPlanPathsPerKind, left_out)
                          : std::string()));
  return chart.svg();
}

std::string trajectories_side_svg(const json& result) {
  const json& p = result.at("pictures");
  const json& trajectories = result.at("trajectories");
  Chart chart("Paths of chosen nails, side elevation", "horizontal distance from the deck's centre (m)", "height above ground (m)", 900,
              380);
  std::set<std::string> labelled;
  for (const auto& t : trajectories.at("paths")) {
    const std::string why = t.at("why").get<std::string>();
    std::vector<double> r, z;
    for (const auto& q : t.at("points_m")) r.push_back(std::hypot(q.at(0).get<double>(), q.at(1).get<double>())), z.push_back(q.at(2).get<double>());
    chart.polyline(r, z, path_colour(why), labelled.insert(why).second ? "path: " + why : "", 1.0, 0.6);
  }
  const json& board = p.at("board_side");
  if (!board.is_null()) {
    const std::vector<double> d = numbers(board.at("distances_m"));
    if (d.size() != 1 && d.size() != 2)
      throw std::out_of_range(fmt::format("pictures.board_side.distances_m: {} values, expected a ring's one or a board's nearest and farthest", d.size()));
    const double bottom = board.at("bottom_m").get<double>(), top = board.at("top_m").get<double>();
    if (d.size() == 1)
      chart.segments({d[0]}, {bottom}, {d[0]}, {top}, kBoardColour, "target board", 3);
    else
      chart.segments(d, {bottom, bottom}, d, {top, top}, kBoardColour, "target board (nearest and farthest)", 3);
  }
  const double blade_plane = p.at("blade_plane_m").get<double>();
  chart.hline(blade_plane, "#000", fmt::format("blade plane ({:.0f} mm)", 1000 * blade_plane));
  chart.caption(paths_caption(trajectories) + " Distance is from the origin, so a path that turns about it doubles back.");
  return chart.svg();
}

}  // namespace j232::report
