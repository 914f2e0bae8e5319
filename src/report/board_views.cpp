#include "report/board_views.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <set>

#include "flight/deck_outline.hpp"
#include "report/svg_chart.hpp"
#include "scene/j232_setup.hpp"
#include "units/quantity.hpp"

namespace j232::report {

namespace {

const std::string kHitColour = "#0072B2", kPunctureColour = "#D55E00", kZoneColour = "#E69F00", kBoardColour = "#8a8a8a",
                  kUncountedColour = "#b8b8b8";

// The board unrolled onto a grid of 1 deg x 1 cm cells; each cell says whether a target
// triangle (and which label) covers its centre. Drawn as runs of cells: a few hundred
// rectangles instead of thousands of triangles.
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

  void draw(Chart& chart) const {
    bool labelled[3] = {false, false, false};
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < kCols;) {
        const std::uint8_t v = cell[static_cast<std::size_t>(r) * kCols + c];
        int e = c + 1;
        while (e < kCols && cell[static_cast<std::size_t>(r) * kCols + e] == v) ++e;
        if (v != 0) {
          const bool zone = v == 2;
          const std::string label = labelled[v] ? "" : (zone ? "operator zone" : "target board");
          labelled[v] = true;
          chart.rect(c - 180.0, z0 + r * kCell, e - 180.0, z0 + (r + 1) * kCell, zone ? kZoneColour : kBoardColour, zone ? 0.45 : 0.18,
                     label);
        }
        c = e;
      }
  }
};

void draw_marks(Chart& chart, const MarkSample& m, bool plan) {
  std::vector<double> hx, hy, px, py, ux, uy;
  for (const auto* row : m.rows) {
    const auto& p = row->mark.point;
    const double x = plan ? p.x() : azimuth_deg(p.x(), p.y());
    const double y = plan ? p.y() : p.z();
    if (!row->mark.counted) {
      ux.push_back(x), uy.push_back(y);
      continue;
    }
    (row->mark.puncture ? px : hx).push_back(x);
    (row->mark.puncture ? py : hy).push_back(y);
  }
  if (!ux.empty()) chart.points(ux, uy, kUncountedColour, fmt::format("not counted ({})", ux.size()), 1.6);
  chart.points(hx, hy, kHitColour, fmt::format("hit ({})", hx.size()), 1.8);
  chart.points(px, py, kPunctureColour, fmt::format("puncture ({})", px.size()), 2.6);
}

std::string sample_caption(const MarkSample& m) {
  if (m.replicates_shown == m.replicates) return fmt::format("All {} located marks of {} replicates.", m.marks, m.replicates);
  return fmt::format("Marks of the first {} of {} replicates ({} of {} located marks): a fair sample, replicates are independent.",
                     m.replicates_shown, m.replicates, m.rows.size(), m.marks);
}

}  // namespace

double azimuth_deg(double x, double y) { return std::atan2(y, x) / units::degree; }

MarkSample sample_marks(const assess::Assessment& a, std::size_t max_marks) {
  MarkSample m;
  m.replicates = a.replicates;
  m.marks = static_cast<std::size_t>(a.marks + a.uncounted_marks - a.unlocated_marks);
  // The runner kept the marks of its first replicates; take as many whole replicates of
  // those as fit in max_marks.
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
  m.replicates_shown = shown;
  for (std::size_t i = 0; i < end; ++i) m.rows.push_back(&kept[i]);
  return m;
}

std::string hit_map_svg(const scenario::Scenario& s, const scene::Soup& soup, const MarkSample& marks) {
  Chart chart("Hit map: the target board unrolled", "azimuth from straight ahead, counter-clockwise seen from above (deg)",
              "height above ground (m)", 900, 380);
  BoardRaster(soup).draw(chart);
  draw_marks(chart, marks, false);
  chart.hline(s.blade_plane(), "#000", fmt::format("blade plane ({:.0f} mm)", 1000 * s.blade_plane()));
  if (s.criteria.counted_height)
    chart.hline(s.counted_height(), "#444", fmt::format("counted from {:.0f} mm (departs from J232)", 1000 * s.counted_height()));
  const auto stations = s.feed_stations();
  for (std::size_t i = 0; i < stations.size(); ++i)
    chart.vline(azimuth_deg(s.station_x(stations[i]), s.station_y(stations[i])), "#009E73",
                stations.size() > 1 ? fmt::format("feed {}", i + 1) : "feed station");
  chart.x_range(-180, 180);
  chart.x_ticks({-180, -135, -90, -45, 0, 45, 90, 135, 180});
  chart.caption(sample_caption(marks));
  return chart.svg();
}

std::array<std::uint8_t, 3> path_rgb(const std::string& why) {
  if (why == "operator zone") return {0xE6, 0x9F, 0x00};  // kZoneColour
  if (why == "puncture") return {0xD5, 0x5E, 0x00};       // kPunctureColour
  return {0x00, 0x72, 0xB2};                              // kHitColour
}

namespace {
bool scene_has_target_mesh(const scenario::Scenario& s) {
  for (const auto& m : s.meshes)
    if (scenario::is_board(m.label)) return true;
  return false;
}

// The mower, guards, board, tip circles, feed stations and seat seen from above.
void draw_mower_plan(Chart& chart, const scenario::Scenario& s, const scene::Soup& soup) {
  chart.equal_aspect();
  // Vertical faces project to segments (deduplicated to 1 mm); others to filled triangles.
  struct Layer {
    std::vector<double> x0, y0, x1, y1, tx, ty;
    std::set<std::array<long long, 4>> seen;
  };
  // One layer per kind of surface, and one more for flaps (guards of kind "flap"), drawn
  // apart from chain curtains.
  constexpr std::size_t kFlapLayer = scene::kSurfaceKinds;
  std::array<Layer, scene::kSurfaceKinds + 1> layers;
  const std::vector<scenario::GuardSpec> guards = scene::scene_guards(s);
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    const auto kind = soup.labels[t];
    if (kind == scene::Surface::Ground) continue;
    const bool flap = kind == scene::Surface::Guard && soup.guard_index[t] < guards.size() &&
                      guards[soup.guard_index[t]].kind == scenario::GuardSpec::Kind::Flap;
    Layer& layer = layers[flap ? kFlapLayer : static_cast<std::size_t>(kind)];
    const auto& p0 = soup.points[soup.triangles[t][0]];
    const auto& p1 = soup.points[soup.triangles[t][1]];
    const auto& p2 = soup.points[soup.triangles[t][2]];
    const double area = (p1.x() - p0.x()) * (p2.y() - p0.y()) - (p2.x() - p0.x()) * (p1.y() - p0.y());
    const double size = std::max({(p1 - p0).head<2>().squaredNorm(), (p2 - p0).head<2>().squaredNorm(), (p2 - p1).head<2>().squaredNorm()});
    if (std::abs(area) > 1e-3 * size) {
      for (const auto* p : {&p0, &p1, &p2}) layer.tx.push_back(p->x()), layer.ty.push_back(p->y());
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
    layer.x0.push_back(v[best.first]->x()), layer.y0.push_back(v[best.first]->y());
    layer.x1.push_back(v[best.second]->x()), layer.y1.push_back(v[best.second]->y());
  }
  struct Style {
    std::size_t layer;
    const char* label;
    std::string colour;
    double width;
  };
  const auto of = [](scene::Surface kind) { return static_cast<std::size_t>(kind); };
  for (const Style& st : {Style{of(scene::Surface::Housing), "housing (deck, skirt)", "#555555", 1.2},
                          Style{of(scene::Surface::Deflector), "deflector", "#009E73", 2.0},
                          Style{of(scene::Surface::Guard), "chain guard", "#CC79A7", 2.5},
                          Style{kFlapLayer, "flap (belting)", "#222222", 4.0},
                          Style{of(scene::Surface::TargetOutside), "target board", kBoardColour, 2.0},
                          Style{of(scene::Surface::TargetZone), "operator zone board", kZoneColour, 3.0}}) {
    const Layer& layer = layers[st.layer];
    if (!layer.tx.empty()) chart.triangles(layer.tx, layer.ty, st.colour, 0.12, layer.x0.empty() ? st.label : "");
    if (!layer.x0.empty()) chart.segments(layer.x0, layer.y0, layer.x1, layer.y1, st.colour, st.label, st.width);
  }
  for (std::size_t k = 0; k < s.spindles.size(); ++k) {
    const auto& sp = s.spindles[k];
    chart.circle(sp.x, sp.y, sp.blade.tip_radius(), "#000",
                 k == 0 ? fmt::format("blade tip circle{} (r {:.3f} m)", s.spindles.size() > 1 ? "s" : "", sp.blade.tip_radius()) : "",
                 true);
  }
  std::vector<double> fx, fy;
  for (const auto& f : s.feed_stations()) fx.push_back(s.station_x(f)), fy.push_back(s.station_y(f));
  chart.points(fx, fy, "#009E73", "feed station", 4);
  if (s.zone.kind == scenario::OperatorZoneSpec::Kind::Derived)
    chart.points({s.zone.seat_x}, {s.zone.seat_y}, "#000000", "operator seat", 4);
}

std::string path_colour(const std::string& why) {
  const auto c = path_rgb(why);
  return fmt::format("#{:02X}{:02X}{:02X}", c[0], c[1], c[2]);
}

// The plan view draws at most this many paths of each kind: more make a blot inside the deck.
constexpr std::size_t kPlanPathsPerKind = 20;

std::string paths_caption(const std::vector<assess::Trajectory>& paths, std::uint64_t not_kept) {
  std::size_t n[3] = {0, 0, 0};
  for (const auto& t : paths) ++n[t.why == "sample" ? 0 : t.why == "operator zone" ? 1 : 2];
  return fmt::format(
      "{} sampled nails (the first struck in replicate 0), {} that marked the operator zone and {} that punctured the "
      "board elsewhere{}.",
      n[0], n[1], n[2],
      not_kept ? fmt::format(" (at most 100 of each, chosen at random from the whole run; {} more not drawn)", not_kept) : std::string());
}
}  // namespace

std::string plan_view_svg(const scenario::Scenario& s, const scene::Soup& soup, const MarkSample& marks) {
  Chart chart("Plan view: mower, guards, targets and marks", "x, forward (m)", "y, left (m)", 620, 600);
  draw_mower_plan(chart, s, soup);
  draw_marks(chart, marks, true);
  chart.caption(sample_caption(marks));
  return chart.svg();
}

std::string trajectories_plan_svg(const scenario::Scenario& s, const scene::Soup& soup, const std::vector<assess::Trajectory>& paths,
                                  std::uint64_t not_kept) {
  Chart chart("Paths of chosen nails, seen from above", "x, forward (m)", "y, left (m)", 620, 600);
  draw_mower_plan(chart, s, soup);
  // A nail rattles inside the deck before it leaves: that part of each path is drawn faint,
  // and from the last point inside the deck's outline on, bold, so that where nails go
  // out and what they reach can be read.
  const flight::DeckOutline deck(scene::deck_footprint(s, soup).outline);
  std::set<std::string> labelled;
  std::map<std::string, std::size_t> drawn;
  std::size_t left_out = 0;
  for (const auto& t : paths) {
    if (++drawn[t.why] > kPlanPathsPerKind) {
      ++left_out;
      continue;
    }
    std::size_t last_inside = 0;
    bool inside_ever = false;
    for (std::size_t i = 0; i < t.points.size(); ++i)
      if (!deck.empty() && deck.contains(t.points[i].x(), t.points[i].y())) last_inside = i, inside_ever = true;
    std::vector<double> x, y, ox, oy;
    for (std::size_t i = 0; i < t.points.size(); ++i) {
      if (inside_ever && i <= last_inside) x.push_back(t.points[i].x()), y.push_back(t.points[i].y());
      if (!inside_ever || i >= last_inside) ox.push_back(t.points[i].x()), oy.push_back(t.points[i].y());
    }
    const std::string colour = path_colour(t.why);
    if (x.size() > 1) chart.polyline(x, y, colour, "", 0.6, 0.18);
    if (ox.size() > 1) chart.polyline(ox, oy, colour, labelled.insert(t.why).second ? "path: " + t.why : "", 1.2, 0.75);
  }
  chart.caption(paths_caption(paths, not_kept) +
                (deck.empty() ? std::string() : " Inside the deck's outline a path is drawn faint; from where it last left the deck, bold.") +
                (left_out ? fmt::format(" Here at most {} of each kind ({} more in the side elevation).", kPlanPathsPerKind, left_out)
                          : std::string()));
  return chart.svg();
}

std::string trajectories_side_svg(const scenario::Scenario& s, const std::vector<assess::Trajectory>& paths, std::uint64_t not_kept) {
  Chart chart("Paths of chosen nails, side elevation", "horizontal distance from the deck's centre (m)", "height above ground (m)", 900,
              380);
  std::set<std::string> labelled;
  for (const auto& t : paths) {
    std::vector<double> r, z;
    for (const auto& p : t.points) r.push_back(std::hypot(p.x(), p.y())), z.push_back(p.z());
    chart.polyline(r, z, path_colour(t.why), labelled.insert(t.why).second ? "path: " + t.why : "", 1.0, 0.6);
  }
  if (!scene_has_target_mesh(s)) {
    if (s.target.shape == scenario::TargetSpec::Shape::Circle) {
      const double ring = s.reach() + s.target.distance;
      chart.segments({ring}, {s.target.bottom}, {ring}, {s.target_top()}, kBoardColour, "target board", 3);
    } else {  // a board along the deck stands at a range of distances from the centre
      double nearest = HUGE_VAL, farthest = 0;
      const auto outline = scene::board_outline(s);
      for (const auto& p : outline) farthest = std::max(farthest, p.norm());
      for (std::size_t i = 0; i < outline.size(); ++i) {  // nearest: to each side, not only to the corners
        const Eigen::Vector2d &a = outline[i], &b = outline[(i + 1) % outline.size()], d = b - a;
        const double t = std::clamp(-a.dot(d) / std::max(d.squaredNorm(), 1e-18), 0.0, 1.0);
        nearest = std::min(nearest, (a + t * d).norm());
      }
      chart.segments({nearest, farthest}, {s.target.bottom, s.target.bottom}, {nearest, farthest}, {s.target_top(), s.target_top()}, kBoardColour,
                     "target board (nearest and farthest)", 3);
    }
  }
  chart.hline(s.blade_plane(), "#000", fmt::format("blade plane ({:.0f} mm)", 1000 * s.blade_plane()));
  chart.caption(paths_caption(paths, not_kept) + " Distance is from the origin, so a path that turns about it doubles back.");
  return chart.svg();
}

}  // namespace j232::report
