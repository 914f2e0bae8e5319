#include "scene/j232_setup.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <stdexcept>

#include "scenario/input_error.hpp"
#include "scene/mesh_io.hpp"
#include "scene/operator_zone.hpp"
#include "units/arc.hpp"
#include "units/quantity.hpp"

namespace j232::scene {

namespace {

// Sides of a one-spindle deck's outline: the generated round deck's plate, skirt and skirt
// guards, and the outline the flight tells the deck's inside by. A nail skidding round the
// skirt bounces off each side it passes, so the cost of those rides grows with the sides;
// the results do not move beyond their noise from 96 to 384 sides (docs/validation.md §3,
// "The round skirt's facets"), and at 48 more of the marks count.
constexpr int kRoundDeckSides = 96;

// A vertical cylindrical patch from azimuth `from` counter-clockwise over `span`,
// between heights z0 and z1, cut at the given azimuths and heights; each quad labelled
// by `label(centre)`.
template <class Label>
void add_wall(Soup& soup, double radius, const std::vector<double>& azimuths, const std::vector<double>& heights, Label label,
              std::uint16_t guard = 0) {
  std::vector<std::vector<std::uint32_t>> ids(azimuths.size());
  for (std::size_t i = 0; i < azimuths.size(); ++i)
    for (double z : heights) ids[i].push_back(soup.add_point({radius * std::cos(azimuths[i]), radius * std::sin(azimuths[i]), z}));
  for (std::size_t i = 0; i + 1 < azimuths.size(); ++i)
    for (std::size_t k = 0; k + 1 < heights.size(); ++k) {
      const double a = 0.5 * (azimuths[i] + azimuths[i + 1]), z = 0.5 * (heights[k] + heights[k + 1]);
      soup.add_quad(ids[i][k], ids[i + 1][k], ids[i + 1][k + 1], ids[i][k + 1], label(Vec3(radius * std::cos(a), radius * std::sin(a), z)),
                    guard);
    }
}

std::vector<double> arc_breaks(double from, double span, double max_step, std::vector<double> extra = {}) {
  const int n = std::max(1, static_cast<int>(std::ceil(span / max_step)));
  std::vector<double> a;
  for (int i = 0; i <= n; ++i) a.push_back(from + span * i / n);
  for (double e : extra) {
    const double rel = std::fmod(e - from + 2 * units::two_pi, units::two_pi);
    if (rel > 1e-9 && rel < span - 1e-9) a.push_back(from + rel);
  }
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end(), [](double x, double y) { return std::abs(x - y) < 1e-9; }), a.end());
  return a;
}

std::vector<double> height_breaks(double z0, double z1, double max_step, std::vector<double> extra = {}) {
  const int n = std::max(1, static_cast<int>(std::ceil((z1 - z0) / max_step)));
  std::vector<double> h;
  for (int i = 0; i <= n; ++i) h.push_back(z0 + (z1 - z0) * i / n);
  for (double e : extra)
    if (e > z0 + 1e-9 && e < z1 - 1e-9) h.push_back(e);
  std::sort(h.begin(), h.end());
  h.erase(std::unique(h.begin(), h.end(), [](double x, double y) { return std::abs(x - y) < 1e-9; }), h.end());
  return h;
}

void add_disc(Soup& soup, double radius, double z, int segments, Surface label) {
  const std::uint32_t centre = soup.add_point({0, 0, z});
  std::vector<std::uint32_t> rim;
  for (int i = 0; i < segments; ++i) {
    const double a = units::two_pi * i / segments;
    rim.push_back(soup.add_point({radius * std::cos(a), radius * std::sin(a), z}));
  }
  for (int i = 0; i < segments; ++i) soup.add_triangle(centre, rim[i], rim[(i + 1) % segments], label);
}

void add_ground(Soup& soup, double half) {
  const auto a = soup.add_point({-half, -half, 0}), b = soup.add_point({half, -half, 0});
  const auto c = soup.add_point({half, half, 0}), d = soup.add_point({-half, half, 0});
  soup.add_quad(a, b, c, d, Surface::Ground);
}

std::optional<double> ray_crossing(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double azimuth);

void add_target_ring(Soup& soup, const scenario::Scenario& s, const OperatorZone& zone) {
  std::vector<double> extra_az, extra_z;
  if (s.zone.kind == scenario::OperatorZoneSpec::Kind::Sector) {
    extra_az = {s.zone.azimuth.from, s.zone.azimuth.to};
    extra_z = {s.zone.bottom, s.zone.top};
  }
  const auto hz = height_breaks(s.target.bottom, s.target_top(), 0.05, extra_z);
  const auto label = [&](const Vec3& c) { return zone.contains(c) ? Surface::TargetZone : Surface::TargetOutside; };
  if (s.target.shape == scenario::TargetSpec::Shape::Circle) {
    const auto az = arc_breaks(0.0, units::two_pi, units::two_pi / s.target.segments, extra_az);
    add_wall(soup, target_radius(s), az, hz, label);
    return;
  }
  // Along the deck: the hull of the tip circles widened by the distance, in pieces as long
  // as the ring's would be, split where an explicit zone's sector begins or ends.
  const auto outline = board_outline(s);
  const double piece = units::two_pi * target_radius(s) / s.target.segments;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Eigen::Vector2d &p = outline[i], &q = outline[(i + 1) % outline.size()];
    std::vector<double> at;
    const int pieces = std::max(1, static_cast<int>(std::ceil((q - p).norm() / piece)));
    for (int k = 0; k <= pieces; ++k) at.push_back(static_cast<double>(k) / pieces);
    for (const double a : extra_az)
      if (const auto t = ray_crossing(p, q, a)) at.push_back(*t);
    std::sort(at.begin(), at.end());
    for (std::size_t k = 0; k + 1 < at.size(); ++k) {
      if (at[k + 1] - at[k] < 1e-9) continue;
      const Eigen::Vector2d a = p + (q - p) * at[k], b = p + (q - p) * at[k + 1];
      for (std::size_t h = 0; h + 1 < hz.size(); ++h) {
        const Vec3 centre(0.5 * (a.x() + b.x()), 0.5 * (a.y() + b.y()), 0.5 * (hz[h] + hz[h + 1]));
        soup.add_quad(soup.add_point({a.x(), a.y(), hz[h]}), soup.add_point({b.x(), b.y(), hz[h]}), soup.add_point({b.x(), b.y(), hz[h + 1]}),
                      soup.add_point({a.x(), a.y(), hz[h + 1]}), label(centre));
      }
    }
  }
}

// Splits triangles in four until no edge is longer than max_edge, so that a target
// mesh's faces are small enough to carry the operator zone's outline.
Soup subdivide(const Soup& in, double max_edge, std::size_t max_triangles) {
  // Count first: each halving of the longest edge makes four triangles of one.
  double count = 0;
  for (const auto& tri : in.triangles) {
    const Vec3 &p0 = in.points[tri[0]], &p1 = in.points[tri[1]], &p2 = in.points[tri[2]];
    const double longest = std::max({(p1 - p0).norm(), (p2 - p1).norm(), (p0 - p2).norm()});
    count += longest <= max_edge ? 1.0 : std::pow(4.0, std::ceil(std::log2(longest / max_edge)));
  }
  if (count > static_cast<double>(max_triangles))
    throw std::runtime_error(
        fmt::format("subdividing this target mesh to {:g} m faces (to carry the operator zone) would "
                    "make {:.3g} triangles, more than {}: is `scale` right for the file's units?",
                    max_edge, count, max_triangles));
  Soup out;
  std::vector<std::array<Vec3, 3>> work;
  for (std::size_t t = 0; t < in.triangles.size(); ++t) {
    work.clear();
    work.push_back({in.points[in.triangles[t][0]], in.points[in.triangles[t][1]], in.points[in.triangles[t][2]]});
    while (!work.empty()) {
      const auto tri = work.back();
      work.pop_back();
      const double longest = std::max({(tri[1] - tri[0]).norm(), (tri[2] - tri[1]).norm(), (tri[0] - tri[2]).norm()});
      if (longest <= max_edge) {
        out.add_triangle(out.add_point(tri[0]), out.add_point(tri[1]), out.add_point(tri[2]), in.labels[t], in.guard_index[t]);
        continue;
      }
      const Vec3 a = 0.5 * (tri[0] + tri[1]), b = 0.5 * (tri[1] + tri[2]), c = 0.5 * (tri[2] + tri[0]);
      work.push_back({tri[0], a, c});
      work.push_back({a, tri[1], b});
      work.push_back({c, b, tri[2]});
      work.push_back({a, b, c});
    }
  }
  return out;
}

// The convex hull of points in plan, counter-clockwise (Andrew's monotone chain).
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  if (points.size() < 3) return points;
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (const auto& p : points) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// The convex hull, counter-clockwise, of every spindle's tip circle widened by `distance`
// (each circle a polygon of `segments` sides).
std::vector<Eigen::Vector2d> widened_tip_hull(const scenario::Scenario& s, double distance, int segments) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& sp : s.spindles)
    for (int i = 0; i < segments; ++i) {
      const double a = units::two_pi * i / segments, r = sp.blade.tip_radius() + distance;
      points.emplace_back(sp.x + r * std::cos(a), sp.y + r * std::sin(a));
    }
  return convex_hull(std::move(points));
}

// The deck's outline seen from above, counter-clockwise: the convex hull of every
// spindle's tip circle widened by the margin (a round deck of kRoundDeckSides for one spindle).
std::vector<Eigen::Vector2d> deck_outline(const scenario::Scenario& s) {
  if (s.spindles.size() != 1) return widened_tip_hull(s, s.housing.margin, 96);
  const auto& sp = s.spindles.front();
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < kRoundDeckSides; ++i) {
    const double a = units::two_pi * i / kRoundDeckSides, r = s.deck_radius();
    points.emplace_back(sp.x + r * std::cos(a), sp.y + r * std::sin(a));
  }
  return convex_hull(std::move(points));
}

// A vertical wall along a polyline in plan, from z0 to z1, in pieces of at most 0.1 m.
void add_path_wall(Soup& soup, const scenario::PlanPath& path, double z0, double z1, Surface label, std::uint16_t guard = 0) {
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const Eigen::Vector2d p(path[i][0], path[i][1]), q(path[i + 1][0], path[i + 1][1]);
    const int pieces = std::max(1, static_cast<int>(std::ceil((q - p).norm() / 0.1)));
    for (int k = 0; k < pieces; ++k) {
      const Eigen::Vector2d a = p + (q - p) * k / pieces, b = p + (q - p) * (k + 1) / pieces;
      soup.add_quad(soup.add_point({a.x(), a.y(), z0}), soup.add_point({b.x(), b.y(), z0}), soup.add_point({b.x(), b.y(), z1}),
                    soup.add_point({a.x(), a.y(), z1}), label, guard);
    }
  }
}

// What stands on its own, on any deck (generated or a mesh): deflector panels (on arcs
// about the origin or along polylines) and guards hung along polylines (numbered from
// first_guard by their place in housing.guards).
void add_free_parts(Soup& soup, const scenario::HousingSpec& h, std::uint16_t first_guard) {
  for (const auto& d : h.deflectors) {
    if (!d.along.empty()) {
      add_path_wall(soup, d.along, d.bottom, d.top, Surface::Deflector);
      continue;
    }
    const double span = d.azimuth.span();
    add_wall(soup, d.radius, arc_breaks(d.azimuth.from, span, units::two_pi / 96), {d.bottom, d.top},
             [](const Vec3&) { return Surface::Deflector; });
  }
  for (std::size_t g = 0; g < h.guards.size(); ++g)
    if (!h.guards[g].along.empty())
      add_path_wall(soup, h.guards[g].along, h.guards[g].bottom, h.guard_top(h.guards[g]), Surface::Guard,
                    static_cast<std::uint16_t>(first_guard + g));
}

// A discharge chute over an opening whose skirt pieces are `pieces` (outline segments in
// plan): a roof swept from each piece straight outward along the opening's middle
// azimuth, sloping from the opening's top to the chute's mouth, and two side walls.
void add_chute(Soup& soup, const scenario::HousingSpec& h, const scenario::OpeningSpec& o,
               const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& pieces) {
  if (o.chute_length <= 0 || pieces.empty()) return;
  const double skirt_bottom = h.skirt_bottom, top = h.opening_top(o), end_top = h.chute_end_top(o);
  const double mid = o.azimuth.middle();
  const Eigen::Vector2d out = o.chute_length * Eigen::Vector2d(std::cos(mid), std::sin(mid));
  auto rel = [&](const Eigen::Vector2d& p) {
    return std::fmod(std::atan2(p.y(), p.x()) - o.azimuth.from + 2 * units::two_pi, units::two_pi);
  };
  Eigen::Vector2d first = pieces.front().first, last = pieces.front().second;
  for (const auto& [a, b] : pieces) {
    if (rel(a) < rel(first)) first = a;
    if (rel(b) > rel(last)) last = b;
    soup.add_quad(soup.add_point({a.x(), a.y(), top}), soup.add_point({b.x(), b.y(), top}),
                  soup.add_point({b.x() + out.x(), b.y() + out.y(), end_top}), soup.add_point({a.x() + out.x(), a.y() + out.y(), end_top}),
                  Surface::Housing);
  }
  for (const Eigen::Vector2d& p : {first, last})
    soup.add_quad(soup.add_point({p.x(), p.y(), skirt_bottom}), soup.add_point({p.x() + out.x(), p.y() + out.y(), skirt_bottom}),
                  soup.add_point({p.x() + out.x(), p.y() + out.y(), end_top}), soup.add_point({p.x(), p.y(), top}),
                  Surface::Housing);
}

// Where the ray from the origin at `azimuth` crosses the segment p -> q, as the fraction
// of the way along it (none when it misses the segment's inside).
std::optional<double> ray_crossing(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double azimuth) {
  const Eigen::Vector2d d(std::cos(azimuth), std::sin(azimuth)), e = q - p;
  const double denom = d.x() * e.y() - d.y() * e.x();  // d x e
  if (std::abs(denom) < 1e-15) return std::nullopt;
  const double t = (p.x() * d.y() - p.y() * d.x()) / denom;  // p + t e on the ray's line
  const Eigen::Vector2d x = p + t * e;
  if (!(t > 1e-12 && t < 1 - 1e-12) || x.dot(d) <= 0) return std::nullopt;
  return t;
}

}  // namespace

std::vector<SkirtPiece> skirt_pieces(const scenario::Scenario& s) {
  const auto& h = s.housing;
  const auto outline = deck_outline(s);
  // Every azimuth a piece must end at: each opening's and each guard's (given by azimuths).
  std::vector<double> cuts;
  for (const auto& o : h.openings) cuts.insert(cuts.end(), {o.azimuth.from, o.azimuth.to});
  for (const auto& g : h.guards)
    if (g.along.empty()) cuts.insert(cuts.end(), {g.azimuth.from, g.azimuth.to});
  std::vector<SkirtPiece> out;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const auto& p = outline[i];
    const auto& q = outline[(i + 1) % outline.size()];
    const int pieces = std::max(1, static_cast<int>(std::ceil((q - p).norm() / 0.1)));
    std::vector<double> at;
    for (int k = 0; k <= pieces; ++k) at.push_back(static_cast<double>(k) / pieces);
    for (const double a : cuts)
      if (const auto t = ray_crossing(p, q, a)) at.push_back(*t);
    std::sort(at.begin(), at.end());
    for (std::size_t k = 0; k + 1 < at.size(); ++k) {
      if (at[k + 1] - at[k] < 1e-9) continue;  // a cut at a piece's end
      const Eigen::Vector2d a = p + (q - p) * at[k], b = p + (q - p) * at[k + 1], m = 0.5 * (a + b);
      out.push_back({a, b, std::atan2(m.y(), m.x()), i});
    }
  }
  return out;
}

FlapGeometry flap_geometry(const scenario::Scenario& s, const scenario::GuardSpec& g) {
  FlapGeometry f;
  f.bottom = g.bottom;
  if (!g.along.empty()) {
    f.hinge = s.housing.guard_top(g);
    for (std::size_t i = 0; i + 1 < g.along.size(); ++i) f.width += std::hypot(g.along[i + 1][0] - g.along[i][0], g.along[i + 1][1] - g.along[i][1]);
    f.swinging = g.panel_width > 0 ? std::min(g.panel_width, f.width) : f.width;
    return f;
  }
  f.hinge = s.housing.skirt_bottom;  // below the skirt it hangs from the skirt's foot
  for (const auto& piece : skirt_pieces(s)) {
    if (!g.azimuth.contains(piece.azimuth)) continue;
    double top = s.housing.skirt_bottom;
    for (const auto& o : s.housing.openings)
      if (o.azimuth.contains(piece.azimuth)) top = std::max(top, s.housing.opening_top(o));
    if (top <= g.bottom) continue;  // it hangs nowhere here
    f.hinge = std::max(f.hinge, top);
    f.width += (piece.b - piece.a).norm();
  }
  f.swinging = g.panel_width > 0 ? std::min(g.panel_width, f.width) : f.width;
  return f;
}

std::vector<double> opening_widths(const scenario::Scenario& s) {
  std::vector<double> widths(s.housing.openings.size(), 0.0);
  if (mesh_roles(s).housing) return widths;
  if (s.spindles.size() == 1 && s.spindles.front().x == 0.0 && s.spindles.front().y == 0.0 && s.housing.openings.empty()) return widths;
  for (const auto& piece : skirt_pieces(s))
    for (std::size_t o = 0; o < s.housing.openings.size(); ++o)
      if (s.housing.openings[o].azimuth.contains(piece.azimuth)) widths[o] += (piece.b - piece.a).norm();
  return widths;
}

namespace {

// A deck whose outline is a polygon (several spindles, or openings cut in the skirt): the
// plate fanned from the centroid, the skirt in pieces of at most 0.1 m along the outline,
// split where an opening or a guard begins or ends (so that each is cut exactly at its
// azimuths), each piece cut away where an opening is, guards hanging below it (and across
// an opening, up to its top).
void add_outline_housing(Soup& soup, const scenario::Scenario& s, std::uint16_t first_guard) {
  const auto& h = s.housing;
  const double deck_top = h.plate_height();
  const auto outline = deck_outline(s);
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : outline) centroid += p;
  centroid /= static_cast<double>(outline.size());
  const std::uint32_t c = soup.add_point({centroid.x(), centroid.y(), deck_top});
  std::vector<std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>> opening_pieces(h.openings.size());
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const auto& p = outline[i];
    const auto& q = outline[(i + 1) % outline.size()];
    soup.add_triangle(c, soup.add_point({p.x(), p.y(), deck_top}), soup.add_point({q.x(), q.y(), deck_top}), Surface::Housing);
  }
  {
    for (const SkirtPiece& piece : skirt_pieces(s)) {
      const Eigen::Vector2d &a = piece.a, &b = piece.b;
      const double azimuth = piece.azimuth;
      auto quad = [&](double z0, double z1, Surface label, std::uint16_t guard) {
        if (z1 - z0 < 1e-6) return;
        soup.add_quad(soup.add_point({a.x(), a.y(), z0}), soup.add_point({b.x(), b.y(), z0}), soup.add_point({b.x(), b.y(), z1}),
                      soup.add_point({a.x(), a.y(), z1}), label, guard);
      };
      double skirt_from = h.skirt_bottom;
      for (std::size_t o = 0; o < h.openings.size(); ++o)
        if (h.openings[o].azimuth.contains(azimuth)) {
          skirt_from = std::max(skirt_from, h.opening_top(h.openings[o]));
          opening_pieces[o].emplace_back(a, b);
        }
      quad(skirt_from, deck_top, Surface::Housing, 0);
      for (std::size_t g = 0; g < h.guards.size(); ++g)
        if (h.guards[g].along.empty() && h.guards[g].azimuth.contains(azimuth))
          quad(h.guards[g].bottom, skirt_from, Surface::Guard, static_cast<std::uint16_t>(first_guard + g));
    }
  }
  for (std::size_t o = 0; o < h.openings.size(); ++o) add_chute(soup, h, h.openings[o], opening_pieces[o]);
}

// The generated deck plate, skirt, chain guards (numbered from first_guard) and deflectors.
void add_housing(Soup& soup, const scenario::Scenario& s, std::uint16_t first_guard) {
  const auto& h = s.housing;
  const auto& sp = s.spindles.front();
  if (s.spindles.size() > 1 || sp.x != 0.0 || sp.y != 0.0 || !h.openings.empty()) return add_outline_housing(soup, s, first_guard);
  const double deck_top = h.plate_height(), deck_radius = s.deck_radius();
  add_disc(soup, deck_radius, deck_top, kRoundDeckSides, Surface::Housing);
  add_wall(soup, deck_radius, arc_breaks(0.0, units::two_pi, units::two_pi / kRoundDeckSides), {h.skirt_bottom, deck_top},
           [](const Vec3&) { return Surface::Housing; });
  for (std::size_t g = 0; g < h.guards.size(); ++g) {
    const auto& guard = h.guards[g];
    if (!guard.along.empty()) continue;  // hung along its own path (add_free_parts)
    const double span = guard.azimuth.span();
    add_wall(
        soup, deck_radius, arc_breaks(guard.azimuth.from, span, units::two_pi / kRoundDeckSides), {guard.bottom, h.skirt_bottom},
        [](const Vec3&) { return Surface::Guard; }, static_cast<std::uint16_t>(first_guard + g));
  }
}

}  // namespace

std::vector<Eigen::Vector2d> board_outline(const scenario::Scenario& s) {
  return widened_tip_hull(s, s.target.distance, std::max(96, s.target.segments / static_cast<int>(s.spindles.size())));
}

double target_radius(const scenario::Scenario& s) {
  if (s.target.shape == scenario::TargetSpec::Shape::Circle) return s.reach() + s.target.distance;
  double farthest = 0;
  for (const auto& p : board_outline(s)) farthest = std::max(farthest, p.norm());
  return farthest;
}

DeckFootprint deck_footprint(const scenario::Scenario& s, const Soup& soup) {
  DeckFootprint f;
  if (!mesh_roles(s).housing) {
    f.outline = deck_outline(s);
    f.top = s.housing.plate_height();
    f.skirt_bottom = s.housing.skirt_bottom;
    return f;
  }
  f.generated = false;
  std::vector<Eigen::Vector2d> points;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (soup.labels[t] == Surface::Housing)
      for (auto v : soup.triangles[t]) {
        points.emplace_back(soup.points[v].x(), soup.points[v].y());
        f.top = std::max(f.top, soup.points[v].z());
      }
  f.outline = convex_hull(std::move(points));
  return f;
}

MeshRoles mesh_roles(const scenario::Scenario& s) {
  MeshRoles r;
  for (const auto& m : s.meshes) {
    if (m.label == scenario::MeshLabel::Ground) r.ground = true;
    if (m.label == scenario::MeshLabel::Housing) r.housing = true;
    if (scenario::is_board(m.label)) r.target = true;
  }
  return r;
}

double escape_radius(const scenario::Scenario& s, const Soup& soup) {
  // A field's objects are followed until they leave its tallied square (corners included).
  if (s.field.present) return field_ground_half(s);
  double reach = target_radius(s);
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (soup.labels[t] != Surface::Ground)
      for (auto v : soup.triangles[t]) reach = std::max(reach, std::hypot(soup.points[v].x(), soup.points[v].y()));
  return reach + 1.0;
}

double board_near_radius(const Soup& soup) {
  double nearest = HUGE_VAL;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (is_target(soup.labels[t]))
      for (auto v : soup.triangles[t]) nearest = std::min(nearest, std::hypot(soup.points[v].x(), soup.points[v].y()));
  return nearest;
}

std::vector<scenario::GuardSpec> scene_guards(const scenario::Scenario& s) {
  std::vector<scenario::GuardSpec> guards;
  for (const auto& m : s.meshes)
    if (m.label == scenario::MeshLabel::Guard) guards.push_back(m.guard);
  guards.insert(guards.end(), s.housing.guards.begin(), s.housing.guards.end());  // a mesh deck keeps only polyline guards
  if (guards.empty()) guards.emplace_back();
  return guards;
}

namespace {

// Whether a triangle meets the upright cylinder over the plan disc (cx, cy, r) between
// heights z0 and z1: the triangle clipped to the slab, then that convex polygon against the
// disc in plan (a corner inside it, an edge within r of its centre, or the centre inside).
bool meets_cylinder(const std::array<Vec3, 3>& tri, double cx, double cy, double r, double z0, double z1) {
  std::vector<Vec3> poly(tri.begin(), tri.end());
  const auto clip = [&](double level, double side) {  // keep side * (z - level) >= 0
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec3 &a = poly[i], &b = poly[(i + 1) % poly.size()];
      const double da = side * (a.z() - level), db = side * (b.z() - level);
      if (da >= 0) out.push_back(a);
      if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
    poly = std::move(out);
  };
  clip(z0, 1.0);
  if (std::isfinite(z1) && !poly.empty()) clip(z1, -1.0);
  if (poly.empty()) return false;
  const Eigen::Vector2d c(cx, cy);
  double turning = 0;  // sign of the centre's side of each edge, for "centre inside"
  bool positive = true, negative = true;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d a = poly[i].head<2>(), b = poly[(i + 1) % poly.size()].head<2>();
    if ((a - c).norm() < r) return true;
    const Eigen::Vector2d e = b - a;
    const double len2 = e.squaredNorm();
    const double t = len2 > 0 ? std::clamp((c - a).dot(e) / len2, 0.0, 1.0) : 0.0;
    if ((a + t * e - c).norm() < r) return true;
    const double side = e.x() * (c.y() - a.y()) - e.y() * (c.x() - a.x());
    turning += std::abs(side);
    positive = positive && side >= 0, negative = negative && side <= 0;
  }
  return turning > 0 && (positive || negative);
}

// What a mesh may not hold, as the generated set-up's checks refuse the same of its parts:
// ground up into a blade's swept disc (from its lower face up), a housing, deflector or
// guard face within a blade's tip circle at the blade's heights.
void check_mesh_part(const scenario::Scenario& s, std::size_t index, const scenario::MeshFile& m, const Soup& part) {
  const bool ground = m.label == scenario::MeshLabel::Ground;
  if (!(ground || m.label == scenario::MeshLabel::Housing || m.label == scenario::MeshLabel::Deflector ||
        m.label == scenario::MeshLabel::Guard))
    return;
  for (std::size_t k = 0; k < s.spindles.size(); ++k) {
    const auto& sp = s.spindles[k];
    const double bottom = sp.geometry.height - 0.5 * sp.geometry.thickness;
    const double top = ground ? HUGE_VAL : sp.geometry.height + 0.5 * sp.geometry.thickness + sp.geometry.edge.sail_height;
    const double tip = sp.blade.tip_radius();
    for (const auto& t : part.triangles) {
      const std::array<Vec3, 3> tri{part.points[t[0]], part.points[t[1]], part.points[t[2]]};
      if (!meets_cylinder(tri, sp.x, sp.y, tip, bottom, top)) continue;
      const std::string blade = s.spindles.size() > 1 ? fmt::format("spindle {}'s blade", k + 1) : std::string("the blade");
      throw scenario::InputError(
          s.file, m.line, fmt::format("meshes[{}].path", index + 1), m.path,
          ground ? fmt::format("the ground mesh rises inside {}'s tip circle ({:.3g} m) to its lower face ({:.4g} m) or above; "
                               "expected turf below every blade",
                               blade, tip, bottom)
                 : fmt::format("the mesh has a face inside {}'s swept disc (its {:.3g} m tip circle, between {:.4g} and {:.4g} m); "
                               "expected nothing fixed where a blade turns",
                               blade, tip, bottom, top));
    }
  }
}

}  // namespace

Soup build_scene_soup(const scenario::Scenario& s) {
  Soup soup;
  const OperatorZone zone(s.zone, s.blade_plane());
  const MeshRoles replaced = mesh_roles(s);

  // The scenario's meshes first (guards among them numbered first), then whatever of the
  // standard set-up they do not replace.
  std::uint16_t guard = 0;
  double mesh_reach = 0;
  double target_top = -HUGE_VAL;
  std::optional<std::size_t> first_target;
  std::optional<std::size_t> first_housing;
  std::vector<Vec3> housing_points;
  std::size_t zone_faces = 0;  // of the board meshes, in the operator zone and reaching above the counted height
  for (std::size_t i = 0; i < s.meshes.size(); ++i) {
    const auto& m = s.meshes[i];
    Surface label = Surface::Housing;
    switch (m.label) {
      case scenario::MeshLabel::Ground: label = Surface::Ground; break;
      case scenario::MeshLabel::Housing: label = Surface::Housing; break;
      case scenario::MeshLabel::Deflector: label = Surface::Deflector; break;
      case scenario::MeshLabel::Guard: label = Surface::Guard; break;
      case scenario::MeshLabel::Target: label = Surface::TargetOutside; break;
      case scenario::MeshLabel::OperatorZone: label = Surface::TargetZone; break;
    }
    Soup part;
    try {
      part = read_mesh(m.path, label, m.scale, label == Surface::Guard ? guard++ : 0);
      // Plain target meshes carry the scenario's operator zone, face by (small) face.
      if (label == Surface::TargetOutside) part = subdivide(part, 0.05, kMaxSceneTriangles - soup.triangles.size());
      if (soup.triangles.size() + part.triangles.size() > kMaxSceneTriangles)
        throw std::runtime_error(fmt::format("{}: the scene would hold more than {} triangles", m.path, kMaxSceneTriangles));
    } catch (const std::runtime_error& e) {
      throw scenario::InputError(s.file, m.line, fmt::format("meshes[{}].path", i + 1), "", e.what());
    }
    if (label == Surface::TargetOutside)
      for (std::size_t t = 0; t < part.triangles.size(); ++t) {
        const auto& tri = part.triangles[t];
        if (zone.contains((part.points[tri[0]] + part.points[tri[1]] + part.points[tri[2]]) / 3.0)) part.labels[t] = Surface::TargetZone;
      }
    check_mesh_part(s, i, m, part);
    // A board mesh that cannot carry a counted mark is no test (as a generated board's top).
    if ((label == Surface::TargetOutside || label == Surface::TargetZone) && !s.field.present) {
      double highest = -HUGE_VAL;
      for (const auto& p : part.points) highest = std::max(highest, p.z());
      target_top = std::max(target_top, highest);
      if (!first_target) first_target = i;
      for (std::size_t t = 0; t < part.triangles.size(); ++t) {
        const auto& tri = part.triangles[t];
        const double top = std::max({part.points[tri[0]].z(), part.points[tri[1]].z(), part.points[tri[2]].z()});
        zone_faces += part.labels[t] == Surface::TargetZone && top > s.counted_height() + 1e-6;
      }
    }
    if (label != Surface::Ground)
      for (const auto& p : part.points) mesh_reach = std::max(mesh_reach, std::hypot(p.x(), p.y()));
    if (label == Surface::Housing) {
      if (!first_housing) first_housing = i;
      housing_points.insert(housing_points.end(), part.points.begin(), part.points.end());
    }
    soup.append(part);
  }
  // A housing mesh covers the blades: it rises above each blade and reaches beyond its tip
  // circle (a deck scaled wrongly lies under the blade, or within its sweep).
  if (first_housing)
    for (std::size_t k = 0; k < s.spindles.size(); ++k) {
      const auto& sp = s.spindles[k];
      const double top = sp.geometry.height + 0.5 * sp.geometry.thickness + sp.geometry.edge.sail_height;
      double highest = -HUGE_VAL, farthest = 0;
      for (const auto& p : housing_points) highest = std::max(highest, p.z()), farthest = std::max(farthest, std::hypot(p.x() - sp.x, p.y() - sp.y));
      if (highest > top && farthest > sp.blade.tip_radius()) continue;
      const std::string blade = s.spindles.size() > 1 ? fmt::format("spindle {}'s blade", k + 1) : std::string("the blade");
      throw scenario::InputError(s.file, s.meshes[*first_housing].line, fmt::format("meshes[{}].path", *first_housing + 1),
                                 s.meshes[*first_housing].path,
                                 fmt::format("the housing meshes {} ({}); expected a deck over every blade (check the mesh's scale)",
                                             highest <= top ? fmt::format("lie wholly below {}'s top ({:.4g} m)", blade, top)
                                                            : fmt::format("lie within {}'s tip circle", blade),
                                             highest <= top ? fmt::format("their highest point {:.4g} m", highest)
                                                            : fmt::format("{:.3g} m at most from its axis, its tip at {:.3g} m", farthest,
                                                                          sp.blade.tip_radius())));
    }
  if (first_target && !(target_top > s.counted_height() + 1e-6))
    throw scenario::InputError(s.file, s.meshes[*first_target].line, fmt::format("meshes[{}].path", *first_target + 1),
                               s.meshes[*first_target].path,
                               fmt::format("the board meshes reach {:.4g} m, at or below the counted height ({:.4g} m); no mark on "
                                           "them could count, so the test could not fail; expected a board rising above it",
                                           target_top, s.counted_height()));
  if (first_target && zone_faces == 0)
    throw scenario::InputError(s.file, s.meshes[*first_target].line, fmt::format("meshes[{}].path", *first_target + 1),
                               s.meshes[*first_target].path,
                               "no face of the board meshes above the counted height lies in the operator zone: no counted mark "
                               "could fall in it, so its criteria could not fail; expected an operator zone ([operator_zone]) on "
                               "the board");
  // A field has no board, and its turf reaches beyond the tallied square.
  const bool board = !s.field.present;
  const double ground_half = board ? target_radius(s) + 2.0 : field_ground_half(s) + 2.0;
  if (!s.meshes.empty()) {
    // Only what the meshes leave to be generated; the generated guards follow the mesh guards.
    Soup generated;
    if (!replaced.ground) add_ground(generated, board ? std::max(ground_half, mesh_reach + 2.0) : ground_half);
    if (!replaced.housing) add_housing(generated, s, guard);
    add_free_parts(generated, s.housing, guard);
    if (!replaced.target && board) add_target_ring(generated, s, zone);
    soup.append(generated);
    return soup;
  }
  add_ground(soup, ground_half);
  add_housing(soup, s, 0);
  add_free_parts(soup, s.housing, 0);
  if (board) add_target_ring(soup, s, zone);
  return soup;
}

}  // namespace j232::scene
