#include "report/hazard_report.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <cstdlib>
#include <fmt/format.h>

#include "assess/model_version.hpp"
#include "report/display_units.hpp"
#include "report/html_page.hpp"
#include "report/html_table.hpp"
#include "report/svg_chart.hpp"
#include "units/quantity.hpp"

namespace j232::report {

using json = nlohmann::ordered_json;
using field::Estimate;

namespace {

json estimate_json(const Estimate& e) { return {{"value", e.value}, {"low", e.low}, {"high", e.high}}; }

// Each direction's hazard distances (hazard.json's and compare.json's "hazard_distance").
json hazard_distances_json(const std::vector<field::DirectionCurve>& directions) {
  json distances = json::array();
  for (const auto& d : directions) {
    distances.push_back({{"direction", d.direction},
                         {"meaning", d.meaning},
                         {"deck_extent_m", d.deck_extent},
                         {"estimate_m", d.hazard_distance},
                         {"conservative_m", d.hazard_distance_upper},
                         {"beyond_range", d.beyond_range},
                         {"conservative_beyond_range", d.upper_beyond_range}});
    json setbacks = json::array();
    for (const auto& b : d.setbacks)
      setbacks.push_back({{"acceptable_area_m2", 1 / b.acceptable_density},
                          {"estimate_m", b.estimate},
                          {"conservative_m", b.conservative},
                          {"beyond_range", b.beyond_range},
                          {"conservative_beyond_range", b.conservative_beyond_range}});
    distances.back()["at_other_acceptable_densities"] = setbacks;
  }
  return distances;
}

// Each direction's curve, point by point (hazard.json's and compare.json's "directions").
json direction_curves_json(const std::vector<field::DirectionCurve>& directions) {
  json curves = json::array();
  for (const auto& d : directions) {
    json points = json::array();
    for (std::size_t k = 0; k < d.distance.size(); ++k) {
      json point = {{"distance_m", d.distance[k]}, {"density_per_m2", estimate_json(d.density[k])}};
      if (!d.vertical.empty()) point["vertical_flux_per_m2"] = estimate_json(d.vertical[k]);
      point["exposure_per_m2"] = estimate_json(d.exposure[k]);
      point["p_struck"] = estimate_json(d.probability[k]);
      points.push_back(point);
    }
    curves.push_back({{"direction", d.direction}, {"meaning", d.meaning}, {"points", points}});
  }
  return curves;
}

const char* side_name(scenario::FieldPlaneSpec::Side s) {
  switch (s) {
    case scenario::FieldPlaneSpec::Side::Left: return "left";
    case scenario::FieldPlaneSpec::Side::Right: return "right";
    case scenario::FieldPlaneSpec::Side::Front: return "front";
    case scenario::FieldPlaneSpec::Side::Rear: return "rear";
  }
  return "?";
}
const char* receptor_name(scenario::FieldPlaneSpec::Receptor r) {
  return r == scenario::FieldPlaneSpec::Receptor::Person ? "person" : "vehicle";
}
const char* kind_name(scenario::FieldObjectSpec::Kind k) { return k == scenario::FieldObjectSpec::Kind::SteelBall ? "steel_ball" : "stone"; }

// A probability chart's logarithmic axis: from the decade above the highest value drawn
// (at most 1; a value at a power of ten is that decade's end) down to the lowest's decade,
// eight decades at most and one at least.
void probability_log_axis(Chart& chart, double highest, double lowest) {
  const double top = std::min(1.0, std::pow(10.0, std::ceil(std::log10(highest) - 1e-9)));
  chart.y_log_range(std::max(top * 1e-8, std::min(top / 10, std::pow(10.0, std::floor(std::log10(lowest) + 1e-9)))), top);
}

// A hazard distance in words: `d` metres, or the deck's edge when it is no farther, or only
// "beyond" the range when the density never falls low enough within it.
std::string distance_words(double d, bool beyond, double deck_extent, double range, const DisplayUnits& u) {
  if (beyond) return fmt::format("beyond {:.0f} {} (the range)", u.length(range), u.length_unit());
  if (d <= deck_extent + 1e-9) return fmt::format("the deck's edge ({:.1f} {})", u.length(deck_extent), u.length_unit());
  return fmt::format("{:.0f} {}", u.length(d), u.length_unit());
}
std::string distance_words(const field::DirectionCurve& c, bool conservative, double range, const DisplayUnits& u) {
  return distance_words(conservative ? c.hazard_distance_upper : c.hazard_distance, conservative ? c.upper_beyond_range : c.beyond_range,
                        c.deck_extent, range, u);
}
// The same from a "hazard_distance" entry of hazard.json or compare.json.
std::string distance_words(const json& c, bool conservative, double range, const DisplayUnits& u) {
  return distance_words(c.at(conservative ? "conservative_m" : "estimate_m").get<double>(),
                        c.at(conservative ? "conservative_beyond_range" : "beyond_range").get<bool>(), c.at("deck_extent_m").get<double>(), range, u);
}
// An {value, low, high} of the JSON as an Estimate.
Estimate estimate_of(const json& e) { return {e.at("value").get<double>(), e.at("low").get<double>(), e.at("high").get<double>()}; }

// Words written in SI (a direction's meaning, a compared figure's name) in the display's
// units: unchanged in SI; in US units "per m2" as "per ft2", "at least 79 J" as "at least 58.3 ft-lb".
std::string in_units(std::string words, const DisplayUnits& u) {
  if (!u.us) return words;
  for (std::size_t at = words.find(" m2"); at != std::string::npos; at = words.find(" m2", at)) words.replace(at, 3, " ft2");
  const std::string least = "at least ";
  for (std::size_t at = words.find(least); at != std::string::npos; at = words.find(least, at + 1)) {
    const std::size_t number = at + least.size(), unit = words.find(" J", number);
    if (unit == std::string::npos) break;
    char* end = nullptr;
    const double joules = std::strtod(words.c_str() + number, &end);
    if (end != words.c_str() + unit) continue;  // not "at least <number> J"
    words.replace(number, unit + 2 - number, fmt::format("{:.3g} ft-lb", DisplayUnits{true}.energy(joules)));
  }
  return words;
}

// A colour for a share t in [0, 1] of a log scale (light yellow to dark red).
std::string heat(double t) {
  static const double stops[][3] = {{255, 255, 204}, {254, 217, 118}, {253, 141, 60}, {227, 26, 28}, {128, 0, 38}};
  t = std::clamp(t, 0.0, 1.0) * 4;
  const int i = std::min(3, static_cast<int>(t));
  const double u = t - i;
  auto c = [&](int k) { return static_cast<int>(std::lround(stops[i][k] + u * (stops[i + 1][k] - stops[i][k]))); };
  return fmt::format("#{:02x}{:02x}{:02x}", c(0), c(1), c(2));
}

// A plan view of counts per cell (per km mowed, per cell), coarsened to at most ~90 blocks
// across the part of the square that holds any: hazard.json's "plan_views" entry, as the
// page draws it (each block's count per m^2 per km mowed, the blocks holding any, row by row).
// Block (i, j) starts i (j) blocks from -reach cells ahead of (to the left of) the mower's
// centre and spans `block` cells a side, but the last row and column, which end at +reach
// (when the square's edge cuts them short).
int block_span(int b, int reach, int block) { return std::min(block, 2 * reach - b * block); }
json plan_view_json(const field::HazardLayout& l, const std::vector<double>& cells) {
  const int n = l.cells();
  int reach = 1;
  for (int iy = 0; iy < n; ++iy)
    for (int ix = 0; ix < n; ++ix)
      if (cells[static_cast<std::size_t>(iy * n + ix)] > 0)
        reach = std::max({reach, std::abs(ix - l.half_cells) + 1, std::abs(iy - l.half_cells) + 1});
  reach = std::min(l.half_cells, reach + 2);
  const int block = std::max(1, (2 * reach + 89) / 90);
  reach = std::min(l.half_cells, (reach + block - 1) / block * block);
  const int blocks = (2 * reach + block - 1) / block;
  json dense = json::array();
  for (int by = 0; by < blocks; ++by)
    for (int bx = 0; bx < blocks; ++bx) {
      const int wx = block_span(bx, reach, block), wy = block_span(by, reach, block);
      double sum = 0;
      for (int iy = 0; iy < wy; ++iy)
        for (int ix = 0; ix < wx; ++ix) {
          const int cx = l.half_cells - reach + bx * block + ix, cy = l.half_cells - reach + by * block + iy;
          sum += cells[static_cast<std::size_t>(cy * n + cx)];
        }
      const double area = (wx * l.cell) * (wy * l.cell);
      if (sum / area > 0) dense.push_back({bx, by, sum / area});
    }
  return {{"cell_m", l.cell},
          {"reach_cells", reach},
          {"block_cells", block},
          {"note", "the square from -reach_cells to +reach_cells cells about the mower's centre (x ahead, y to its left) in blocks of "
                   "block_cells x block_cells cells, block [i, j] starting at (-reach_cells + i block_cells, -reach_cells + j "
                   "block_cells) cells, the last row and column cut short at +reach_cells; each [i, j, per m2 per km mowed], the "
                   "blocks holding none left out"},
          {"blocks", dense}};
}

// The plan view of `view` (plan_view_json's) with the deck's outline, its travel, the planes
// (hazard.json's) and the hazard distance each way drawn.
std::string plan_view(const json& view, const json& outline, const json& planes, const json& distances, double range, const std::string& title,
                      const std::string& what, const DisplayUnits& u) {
  const int reach = view.at("reach_cells").get<int>(), block = view.at("block_cells").get<int>();
  const double l_cell = view.at("cell_m").get<double>();
  double top = 0, bottom = HUGE_VAL;
  std::vector<std::array<double, 3>> density;  // block x, y, per area per mowed in the display's units
  for (const json& b : view.at("blocks")) {
    const double d = u.per_area(u.per_mowed(b.at(2).get<double>()));
    density.push_back({b.at(0).get<double>(), b.at(1).get<double>(), d});
    if (d > 0) top = std::max(top, d), bottom = std::min(bottom, d);
  }
  Chart c(title, fmt::format("ahead of the mower ({})", u.length_unit()), fmt::format("to its left ({})", u.length_unit()), 640, 640);
  c.equal_aspect();
  const double half = u.length(reach * l_cell), cell = u.length(l_cell);
  c.x_range(-half, half), c.y_range(-half, half);
  const double span = top > bottom ? std::log10(top / bottom) : 1.0;
  for (const auto& [bx, by, d] : density) {
    if (d <= 0) continue;
    const double x0 = -half + bx * block * cell, y0 = -half + by * block * cell;
    const int wx = block_span(static_cast<int>(bx), reach, block), wy = block_span(static_cast<int>(by), reach, block);
    c.rect(x0, y0, x0 + wx * cell, y0 + wy * cell, heat(std::log10(d / bottom) / span), 1.0, "");
  }
  if (!outline.empty()) {
    std::vector<double> x, y;
    for (const json& p : outline) x.push_back(u.length(p.at(0).get<double>())), y.push_back(u.length(p.at(1).get<double>()));
    x.push_back(u.length(outline.at(0).at(0).get<double>())), y.push_back(u.length(outline.at(0).at(1).get<double>()));
    c.line(x, y, "#000000", "the mower's deck", false);
  }
  c.segments({0.0}, {0.0}, {std::max(2.0, 0.2 * half)}, {0.0}, "#0072B2", "its travel", 2.5);
  for (const json& p : planes) {
    const std::string side = p.at("side").get<std::string>(), name = p.at("name").get<std::string>();
    const double distance = p.at("distance_m").get<double>();
    const double at = u.length(side == "left" || side == "front" ? distance : -distance);
    if (std::abs(at) > half) continue;
    if (side == "left" || side == "right")
      c.hline(at, "#009E73", "plane '" + name + "'");
    else
      c.vline(at, "#009E73", "plane '" + name + "'");
  }
  // The hazard distance each way (the estimate): beside the path a line along it, ahead and
  // behind a line across it. Off the map (or beyond the range tallied) it is named in the caption.
  std::string drawn, off_map;
  for (const json& d : distances) {
    const std::string direction = d.at("direction").get<std::string>();
    const double hazard_distance = d.at("estimate_m").get<double>();
    const bool beyond_range = d.at("beyond_range").get<bool>();
    const bool beside = direction == "left" || direction == "right";
    const double at = (direction == "left" || direction == "front" ? 1.0 : -1.0) * u.length(hazard_distance);
    if (beyond_range || std::abs(at) > half) {
      off_map += fmt::format("{}{} {} (off this map)", off_map.empty() && drawn.empty() ? "" : ", ", direction,
                             beyond_range ? fmt::format("beyond the {} {} tallied", u.figure(u.length(range)), u.length_unit())
                                          : fmt::format("{:.3g} {}", u.length(hazard_distance), u.length_unit()));
      continue;
    }
    drawn += fmt::format("{}{} {:.3g} {}", drawn.empty() ? "" : ", ", direction, u.length(hazard_distance), u.length_unit());
    if (beside)
      c.hline(at, "#D55E00", "");
    else
      c.vline(at, "#D55E00", "");
  }
  c.caption((top > 0 ? fmt::format("{} per {} around the mower, per {} mowed, in {:.3g} {} cells: colours on a log scale from {:.2g} (pale) "
                                   "to {:.2g} (dark) per {}.",
                                   what, u.area_unit(), u.mowed(), block * cell, u.length_unit(), bottom, top, u.area_unit())
                     : what + ": none in the tallied square.") +
            (drawn.empty() && off_map.empty() ? std::string()
                                              : " Orange dashed lines: the hazard distance each way (the estimate): " + drawn + off_map + "."));
  return "<figure>" + c.svg() + "</figure>\n";
}

// A per-cell count of every kind, weighted as the field holds each kind, per km mowed.
std::vector<double> per_km(const field::FieldSimulator& sim, const field::HazardRun& run, std::vector<std::uint64_t> field::HazardTally::*cells) {
  const std::vector<double> w = field::weights_per_object(sim, run);
  std::vector<double> out((run.strata.front().*cells).size());
  for (std::size_t k = 0; k < run.strata.size(); ++k)
    for (std::size_t i = 0; i < out.size(); ++i) out[i] += 1000 * w[k] * static_cast<double>((run.strata[k].*cells)[i]);
  return out;
}

}  // namespace

std::vector<Assumption> hazard_assumptions(const scenario::Scenario& s) {
  std::vector<Assumption> a;
  const scenario::FieldSpec& f = s.field;
  a.push_back({"Impact: the blade's impulse-momentum model (hub and pinned links) striking each object, a rigid sphere, where the "
               "blade's edge, bevel, faces or sail first touch it (continuous contact search), along the geometric normal, with "
               "Coulomb friction and a restitution that creates no energy; every contact of a pass is resolved",
               "report 445-1 Ch. 2, generalised (docs/model.md §5.1)"});
  for (const auto& o : f.objects)
    a.push_back({fmt::format("Objects '{}' ({}): sphere-equivalent size lognormal, median {:.1f} mm, geometric spread {:g}, cut to "
                             "{:.1f}-{:.1f} mm; {:g} kg/m3; {:g} per m2; sunk {:.0f} % of their size into the turf; on the blade "
                             "restitution {}, friction {:g}; drag coefficient {:g}",
                             o.name, kind_name(o.kind), o.median_size * 1e3, o.spread, o.min_size * 1e3, o.max_size * 1e3, o.density,
                             o.per_area, 100 * o.embedment,
                             o.restitution ? fmt::format("{:g}", *o.restitution) : std::string("as the scenario's [restitution]"),
                             o.friction, o.drag_coefficient),
                 o.kind == scenario::FieldObjectSpec::Kind::SteelBall
                     ? "scenario; steel 7850 kg/m3, smooth sphere Cd 0.47 (handbook values)"
                     : "scenario, or estimates (docs/model.md §9: stone density 2600-2700 kg/m3 from handbooks; size, number, "
                       "embedment, restitution and drag estimates)"});
  a.push_back({fmt::format("Mowing at {:.1f} km/h straight along +x over level turf; each object met as the mower reaches it, lying "
                           "still; the air still",
                           f.ground_speed * 3.6),
               "scenario (ground speed an estimate unless given)"});
  if (f.support_height > 0)
    a.push_back({fmt::format("Each object rests on what holds it up (crowns and clods of the ground, thatch, clumps): its resting "
                             "level above the plane the wheels ride on {} with mean {:.3g} mm, drawn for each object. One "
                             "whose top then stands above the blades' lower face can be struck; one standing at or above the deck's "
                             "front gap is pushed aside by the deck, not struck; the turf the thrown objects meet is that plane",
                             f.support_shape == scenario::FieldSpec::SupportShape::HalfNormal ? "half-normal" : "exponential",
                             1e3 * f.support_height),
                 "scenario (field.support_height and support_shape: estimates; docs/model.md §9)"});
  else
    a.push_back({"Every object lies on the plane the wheels ride on (field.support_height 0): only those standing above the blades' "
                 "lower face, or lifted, are struck",
                 "scenario (a stated simplification; docs/model.md §9)"});
  if (f.updraft_speed > 0)
    a.push_back({fmt::format("The air the blades draw up, {:g} m/s at the turf, lifts an object into the blades' plane when its drag "
                             "exceeds its weight; the others are struck where they lie",
                             f.updraft_speed),
                 "scenario (field.updraft_speed: an estimate; docs/model.md §9)"});
  else
    a.push_back({"No lift of objects into the blades by the air the blades draw up (field.updraft_speed 0: objects are struck where "
                 "they lie)",
                 "docs/model.md §9 (a stated simplification)"});
  {
    std::string skid, roll;
    for (const auto& o : f.objects) (o.rolls ? roll : skid) += fmt::format("{}'{}'", (o.rolls ? roll : skid).empty() ? "" : ", ", o.name);
    a.push_back({fmt::format("On the ground, an object too slow to bounce on{}{}{}",
                             skid.empty() ? "" : fmt::format(" skids at the turf's friction ({:g}), slowed by drag too ({})", s.ground.friction, skid),
                             skid.empty() || roll.empty() ? "" : ";",
                             roll.empty() ? ""
                                          : fmt::format(" rolls ({}): it slips at the turf's friction until its contact stops slipping, then "
                                                        "rolls, slowed by {:g} g of rolling resistance and by drag",
                                                        roll, s.ground.rolling_resistance)),
                 roll.empty() ? "scenario (an angular stone skids: field.objects.rolls false, the default for stones)"
                              : "scenario (ground.rolling_resistance: an estimate, a golf green's 0.05-0.09 g the low end; docs/model.md §9)"});
    if (!skid.empty())
      a.push_back({fmt::format("An angular stone ({}) does not roll along the mower's steel: each contact with the skirt, plate or a "
                               "guard is the rigid sphere's and leaves it without spin (its flats stop it rolling), so a sustained "
                               "contact skids; a round one rolls along it with no rolling resistance",
                               skid),
                   "model form (j232 uq draws each stone kind's rolls); docs/model.md §5.3"});
  }
  a.push_back({"Flight in the mower's frame (deck, guards, turf as in the J232 model); positions and energies tallied in the ground's "
               "frame at each object's strike (the mower's travel added); a bounce on the turf resolved in the turf's frame",
               "docs/model.md §9"});
  a.push_back({fmt::format("A person is struck hazardously by an object of at least {:g} J; presented area {:g} m2; probability of "
                           "being struck 1 - exp(-q A) for q hazardous impacts per m2 of ground; acceptable: one per {:g} m2",
                           f.person_energy, f.presented_area, f.acceptable_area),
               "DDESB Technical Paper 12 (hazardous fragment: 79 J / 58 ft-lb; 0.58 m2; one per 600 ft2)"});
  a.push_back({fmt::format("A vehicle: an object of at least {:g} J through the windshield band {:.2f}-{:.2f} m above the ground",
                           f.vehicle_energy, f.windshield_bottom, f.windshield_top),
               "estimates (vary them: no published threshold is used here)"});
  // The mower's own: the deck, guards, turf and air, as the J232 report names them.
  for (const auto& item : assumptions(s)) {
    const std::string& w = item.what;
    for (const char* keep : {"Blade edge", "Deck", "Guard", "Flap", "Ground", "Air drag"})
      if (w.rfind(keep, 0) == 0) {
        a.push_back(item);
        break;
      }
  }
  return a;
}

json hazard_json(const field::FieldSimulator& sim, const field::HazardRun& run, const field::HazardSummary& sum, const HazardProvenance& p) {
  const scenario::Scenario& s = sim.scenario();
  const scenario::FieldSpec& f = s.field;
  const field::HazardLayout& layout = run.strata.front().layout;
  const std::vector<double> w = field::weights_per_object(sim, run);
  json objects = json::array();
  for (std::size_t k = 0; k < f.objects.size(); ++k) {
    const auto& o = f.objects[k];
    const field::HazardTally t = field::kind_tally(sim, run, k);
    json strata = json::array();
    for (std::size_t j = 0; j < run.strata.size(); ++j)
      if (const auto& st = sim.stratum(j); st.kind == k)
        strata.push_back({{"smallest_m", st.smallest}, {"largest_m", st.largest}, {"share_of_kind_met", st.share}, {"objects", run.strata[j].objects}});
    json fates = json::object();
    for (int i = 0; i < field::kObjectFates; ++i) fates[field::object_fate_name(static_cast<field::ObjectFate>(i))] = t.fates[static_cast<std::size_t>(i)];
    json cut = json::object();
    for (int i = 1; i < flight::kCutOffReasons; ++i)
      if (t.cut_off_by[static_cast<std::size_t>(i)]) cut[flight::cut_off_name(static_cast<flight::CutOff>(i))] = t.cut_off_by[static_cast<std::size_t>(i)];
    objects.push_back({{"name", o.name},
                       {"kind", kind_name(o.kind)},
                       {"median_size_m", o.median_size},
                       {"spread", o.spread},
                       {"min_size_m", o.min_size},
                       {"max_size_m", o.max_size},
                       {"density_kg_m3", o.density},
                       {"per_m2", o.per_area},
                       {"embedment", o.embedment},
                       {"restitution_on_blade", o.restitution ? json(*o.restitution) : json("scenario [restitution]")},
                       {"friction_on_blade", o.friction},
                       {"drag_coefficient", o.drag_coefficient},
                       {"on_the_ground", o.rolls ? "rolls" : "skids"},
                       {"met_per_km", 1000 * sim.objects_per_metre(k)},
                       {"share_that_can_reach_a_blade", sim.reach_share(k)},
                       {"simulated",
                        {{"objects", t.objects},
                         {"note", "drawn among the sizes that can reach a blade, in strata of size (each about an equal share of the "
                                  "kind's mass), each given the same number of objects and weighted by its share"},
                         {"size_strata", strata},
                         {"fates", fates},
                         {"cut_off_by", cut},
                         {"at_rest_under_deck", t.at_rest_under_deck},
                         {"left_tallied_square", t.left_square},
                         {"first_landed_beyond_square", t.landed_beyond_square},
                         {"hazardous_impacts_beyond_square", t.hazardous_beyond_square},
                         {"objects_with_impacts_beyond_record", t.overflow},
                         {"objects_a_knife_rode_over", t.ridden_over},
                         {"objects_pushed_along_by_an_arm", t.pushed_along}}}});
  }
  const json distances = hazard_distances_json(sum.directions), curves = direction_curves_json(sum.directions);
  json planes = json::array();
  for (const auto& r : sum.planes) {
    json pj = {{"name", r.plane.name},
               {"side", side_name(r.plane.side)},
               {"distance_m", r.plane.distance},
               {"receptor", receptor_name(r.plane.receptor)},
               {"crossings_per_km", r.crossings_per_km},
               {"hazardous_per_km", estimate_json(r.hazardous_per_km)},
               {"hazardous_per_m2_per_pass", r.along_path ? estimate_json(r.hazardous_per_area) : json(nullptr)},
               {"crossings_per_km_by_height", {{"band_m", field::kHeightBand}, {"per_km", r.per_km_by_height}, {"note", "the last band: 4 m and above"}}}};
    if (r.plane.receptor == scenario::FieldPlaneSpec::Receptor::Person && r.along_path) {
      pj["p_struck_per_pass"] = estimate_json(r.probability);
      pj["p_struck_per_season"] = estimate_json(r.probability_per_season);
      pj["people_struck_per_season"] = estimate_json(r.people_struck_per_season);
    }
    if (!r.along_path)
      pj["note"] = "a plane across the path, this far ahead of (behind) the mower at each object's strike: per km only";
    planes.push_back(pj);
  }
  json reach = json::array();
  double thrown = 0;
  for (std::size_t k = 0; k < run.strata.size(); ++k)
    for (auto c : run.strata[k].farthest) thrown += w[k] * static_cast<double>(c);
  for (double d : {1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 50.0, 75.0, 100.0, 150.0, 200.0}) {
    double beyond = 0;
    for (std::size_t k = 0; k < run.strata.size(); ++k)
      for (std::size_t i = static_cast<std::size_t>(d / 0.25); i < run.strata[k].farthest.size(); ++i)
        beyond += w[k] * static_cast<double>(run.strata[k].farthest[i]);
    reach.push_back({{"distance_m", d}, {"share_beyond", thrown > 0 ? beyond / thrown : 0.0}});
  }
  // Where objects come down, as the page's plan views draw it, with the deck's outline.
  json outline = json::array();
  for (const auto& q : sim.mower().footprint().outline) outline.push_back({q.x(), q.y()});
  const json plan_views = {{"deck_outline_m", outline},
                           {"first_landings_per_m2_per_km", plan_view_json(layout, per_km(sim, run, &field::HazardTally::landings))},
                           {"hazardous_impacts_per_m2_per_km", plan_view_json(layout, per_km(sim, run, &field::HazardTally::hazardous))}};
  json scenario = scenario_json(s);
  for (const char* key : {"nail", "feed", "target", "operator_zone", "board", "criteria", "uncertainty"}) scenario.erase(key);
  json assumed = json::array();
  for (const auto& a : hazard_assumptions(s)) assumed.push_back({{"what", a.what}, {"source", a.source}});
  return {
      {"title", s.title},
      {"kind", "thrown-object hazard in the field (j232 hazard)"},
      {"model_version", assess::kModelVersion},
      {"physics_model", assess::kModelPhysics},
      {"valid", sum.valid},
      {"invalid_reason", sum.invalid_reason},
      {"warnings", sum.warnings},
      {"frame", "the ground's at each object's strike: origin at the mower's centre then, x along its travel, y to its left"},
      {"field",
       {{"ground_speed_m_s", f.ground_speed},
        {"updraft_speed_m_s", f.updraft_speed},
        {"passes_per_season", f.passes_per_season},
        {"people_per_pass", f.people_per_pass},
        {"support_height_mean_m", f.support_height},
        {"support_shape", f.support_shape == scenario::FieldSpec::SupportShape::HalfNormal ? "half_normal" : "exponential"},
        {"cut_width_m", sum.cut_width},
        {"objects_met_per_km", sum.objects_per_km},
        {"objects_that_can_reach_a_blade_per_km", sum.reaching_per_km},
        {"objects", objects},
        {"range_m", layout.range},
        {"cell_m", layout.cell},
        {"person_energy_J", f.person_energy},
        {"presented_area_m2", f.presented_area},
        {"acceptable_area_m2", f.acceptable_area},
        {"acceptable_density_per_m2", sum.acceptable_density},
        {"person_height_m", f.person_height},
        {"vehicle_energy_J", f.vehicle_energy},
        {"windshield_m", {f.windshield_bottom, f.windshield_top}}}},
      {"objects", {{"simulated", sum.objects}, {"thrown", sum.thrown}, {"cut_off", sum.cut_off}, {"thrown_per_km", sum.thrown_per_km}}},
      {"throw",
       {{"exit_speed_m_s", {{"mean", sum.exit_speed_mean}, {"q95", sum.exit_speed_q95}}},
        {"last_strike_speed_m_s", {{"mean", sum.last_strike_speed_mean}, {"q95", sum.last_strike_speed_q95}}},
        {"launch_elevation_deg_mean", sum.launch_elevation_mean},
        {"first_landing_outside_deck_share", sum.landed_outside_deck_share},
        {"farthest_ground_contact_m", sum.max_distance},
        {"reach", reach}}},
      {"hazard_distance", distances},
      {"directions", curves},
      {"planes", planes},
      {"plan_views", plan_views},
      {"assumptions", assumed},
      {"scenario", scenario},
      {"provenance",
       {{"version", p.version},
        {"git_revision", p.git_revision},
        {"date", p.date},
        {"seed", p.seed},
        {"threads", p.threads},
        {"ranks", p.ranks},
        {"wall_time_s", p.wall_seconds},
        {"objects_per_second", p.wall_seconds > 0 ? static_cast<double>(sum.objects) / p.wall_seconds : 0.0}}},
  };
}

std::string hazard_csv(const field::HazardSummary& sum) {
  std::string o = "what,name,distance_m,density_per_m2,density_low,density_high,p_struck,p_struck_low,p_struck_high,per_km,per_km_low,per_km_high\n";
  // A direction's density: what a person there meets (beside the path, the larger of the
  // ground's impacts and the vertical plane's crossings per m2; hazard.json has both).
  for (const auto& d : sum.directions)
    for (std::size_t k = 0; k < d.distance.size(); ++k) {
      const auto &q = d.exposure[k], &p = d.probability[k];
      o += fmt::format("direction,{},{:g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},,,\n", d.direction, d.distance[k], q.value, q.low, q.high,
                       p.value, p.low, p.high);
    }
  for (const auto& r : sum.planes) {
    const auto& h = r.hazardous_per_km;
    const auto& a = r.hazardous_per_area;
    const bool person = r.plane.receptor == scenario::FieldPlaneSpec::Receptor::Person && r.along_path;
    const std::string area = r.along_path ? fmt::format("{:.6g},{:.6g},{:.6g}", a.value, a.low, a.high) : ",,";
    o += fmt::format("plane,{},{:g},{},{},{},{},{:.6g},{:.6g},{:.6g}\n", r.plane.name, r.plane.distance, area,
                     person ? fmt::format("{:.6g}", r.probability.value) : "", person ? fmt::format("{:.6g}", r.probability.low) : "",
                     person ? fmt::format("{:.6g}", r.probability.high) : "", h.value, h.low, h.high);
  }
  return o;
}

std::string hazard_text(const field::HazardSummary& sum, double range, const DisplayUnits& u) {
  std::string o;
  if (!sum.valid) o += fmt::format("  NO HAZARD ASSESSMENT: {}\n", sum.invalid_reason);
  o += fmt::format("  {:.0f} objects met per {} mowed ({:.2f} {} cut), {:.0f} thrown per {}; speed off the last blade strike {:.0f} {} "
                   "mean (95th percentile {:.0f}), off the first {:.0f} {} mean\n",
                   u.per_mowed(sum.objects_per_km), u.mowed(), u.length(sum.cut_width), u.length_unit(), u.per_mowed(sum.thrown_per_km),
                   u.mowed(), u.speed(sum.last_strike_speed_mean), u.speed_unit(), u.speed(sum.last_strike_speed_q95),
                   u.speed(sum.exit_speed_mean), u.speed_unit());
  o += "  Hazard distance (hazardous impacts fall below the acceptable density), estimate / conservative (95 % upper bound):\n";
  for (const auto& d : sum.directions)
    o += fmt::format("    {:<6} {:>28} / {}\n", d.direction, distance_words(d, false, range, u),
                     distance_words(d, true, range, u));
  for (const auto& r : sum.planes) {
    o += fmt::format("  Plane '{}' ({} {} {}, {}): {:.3g} hazardous per {} mowed (95 %: {:.3g}-{:.3g})\n", r.plane.name,
                     side_name(r.plane.side), u.figure(u.length(r.plane.distance)), u.length_unit(), receptor_name(r.plane.receptor),
                     u.per_mowed(r.hazardous_per_km.value), u.mowed(), u.per_mowed(r.hazardous_per_km.low), u.per_mowed(r.hazardous_per_km.high));
    if (r.plane.receptor == scenario::FieldPlaneSpec::Receptor::Person && r.along_path && r.probability_per_season.value != r.probability.value)
      o += fmt::format("    a person there: P(struck) {:.3g} in one pass, {:.3g} (95 %: {:.3g}-{:.3g}) over the season's passes\n",
                       r.probability.value, r.probability_per_season.value, r.probability_per_season.low, r.probability_per_season.high);
  }
  return o;
}

std::string hazard_html(const json& result, const DisplayUnits& u) {
  const json& field_json = result.at("field");
  const json& distances = result.at("hazard_distance");
  const json& directions = result.at("directions");
  const json& planes_json = result.at("planes");
  const std::string title = result.at("title").get<std::string>();
  const double person_energy = field_json.at("person_energy_J").get<double>(), acceptable_area = field_json.at("acceptable_area_m2").get<double>();
  std::string o = page_head("Thrown-object hazard: " + title);
  o += fmt::format("<h1>Thrown-object hazard in the field: {}</h1>\n", escape(title));
  if (!result.at("valid").get<bool>())
    o += fmt::format("<p class=\"verdict fail\"><strong>No hazard assessment:</strong> {}</p>\n", escape(result.at("invalid_reason").get<std::string>()));
  if (!result.at("warnings").empty()) {
    o += "<ul class=\"warnings\">\n";
    for (const json& w : result.at("warnings")) o += fmt::format("<li>Warning: {}</li>\n", escape(w.get<std::string>()));
    o += "</ul>\n";
  }
  const json& objects = result.at("objects");
  o += fmt::format(
      "<p>A simulation of this mower at work at {:.1f} {} over turf strewn with objects ({:.2f} {} cut): {:.0f} objects met "
      "per {} mowed, {:.0f} of them of a size that can reach a blade, {:.0f} thrown. {} objects were simulated (a "
      "Monte Carlo sample drawn among the sizes that can reach a blade, in strata of kind and size, so that the few heavy "
      "objects are drawn as often as the many light ones, each weighted by its share). Every figure is an "
      "estimate from that sample, with its 95 % interval; the figures are of the simulated model with its stated "
      "assumptions (below), not a measurement.{}</p>\n",
      u.travel(field_json.at("ground_speed_m_s").get<double>()), u.travel_unit(), u.length(field_json.at("cut_width_m").get<double>()), u.length_unit(),
      u.per_mowed(field_json.at("objects_met_per_km").get<double>()), u.us ? "mile" : "kilometre",
      u.per_mowed(field_json.at("objects_that_can_reach_a_blade_per_km").get<double>()), u.per_mowed(objects.at("thrown_per_km").get<double>()),
      objects.at("simulated").get<std::uint64_t>(),
      u.us ? " Figures in US customary units (ft, mph, ft-lb, per mile mowed); the assumptions quote the scenario's own inputs, and "
             "hazard.json and hazard.csv keep SI units."
           : "");
  o += "<h2>Hazard distances</h2>\n";
  o += fmt::format(
      "<p>How far from the mower a person must be for the hazardous objects (with at least {} {}) they meet in one pass to "
      "fall below one per {} {} for good: beside the path, the larger of those coming down per {} of ground and "
      "those flying or skidding through per {} of the vertical plane there; ahead and behind, those coming down on the "
      "mower's line. The conservative distance uses the 95 % interval's upper end.</p>\n",
      u.figure(u.energy(person_energy)), u.energy_unit(), u.figure(u.area(acceptable_area)), u.area_unit_html(), u.area_unit_html(),
      u.area_unit_html());
  const double range = field_json.at("range_m").get<double>();
  HtmlTable distance_table({"direction", "who", "estimate", "conservative"});
  for (const json& d : distances)
    distance_table.row({d.at("direction").get<std::string>(), escape(in_units(d.at("meaning").get<std::string>(), u)), distance_words(d, false, range, u),
                        distance_words(d, true, range, u)});
  o += distance_table.html();
  // How the setback moves with what is judged acceptable: each distance at other densities.
  o += "<p>How the hazard distance moves with the acceptable density (estimate / conservative; the scenario's in bold):</p>\n";
  std::vector<HtmlCell> header = {"one hazardous impact per"};
  for (const json& d : distances) header.push_back(d.at("direction").get<std::string>());
  HtmlTable setbacks(header);
  for (std::size_t b = 0; !distances.empty() && b < distances.front().at("at_other_acceptable_densities").size(); ++b) {
    const double area = distances.front().at("at_other_acceptable_densities")[b].at("acceptable_area_m2").get<double>();
    const bool own = std::abs(area - acceptable_area) < 1e-9 * area;
    std::vector<HtmlCell> cells = {fmt::format("{}{} {}{}", own ? "<strong>" : "", fmt::format(fmt::runtime(u.us ? "{:.4g}" : "{:.3g}"), u.area(area)),
                                                  u.area_unit_html(), own ? "</strong>" : "")};
    for (const json& d : distances) {
      const json& at = d.at("at_other_acceptable_densities").at(b);
      const double deck = d.at("deck_extent_m").get<double>();
      cells.push_back(fmt::format("{} / {}",
                                  distance_words(at.at("estimate_m").get<double>(), at.at("beyond_range").get<bool>(), deck, range, u),
                                  distance_words(at.at("conservative_m").get<double>(), at.at("conservative_beyond_range").get<bool>(), deck, range, u)));
    }
    setbacks.row(cells);
  }
  o += setbacks.html();

  Chart curves("Probability of being struck by a hazardous object in one pass", fmt::format("distance from the mower ({})", u.length_unit()),
               "probability");
  const double acceptable_p = -std::expm1(-field_json.at("presented_area_m2").get<double>() / acceptable_area);
  const double acceptable_density = field_json.at("acceptable_density_per_m2").get<double>();
  double far = 5;
  for (const json& d : directions)
    for (const json& point : d.at("points")) {
      const Estimate exposure = estimate_of(point.at("exposure_per_m2"));
      if (exposure.value > 0 || exposure.high >= acceptable_density) far = std::max(far, point.at("distance_m").get<double>() + 2);
    }
  far = std::min(far, range);
  // On a logarithmic axis: the probabilities fall by decades with distance, and the acceptable
  // level may lie far above or below the curves. The axis spans the acceptable level and the
  // values drawn, eight decades at most; what lies below its floor (zero among it) is drawn on it.
  double highest = acceptable_p, lowest = acceptable_p;
  for (std::size_t i = 0; i < directions.size(); ++i) {
    std::vector<double> x, p, lo, hi;
    for (const json& point : directions[i].at("points")) {
      if (!(point.at("distance_m").get<double>() <= far)) break;
      const Estimate struck = estimate_of(point.at("p_struck"));
      x.push_back(u.length(point.at("distance_m").get<double>())), p.push_back(struck.value), lo.push_back(struck.low), hi.push_back(struck.high);
    }
    curves.band(x, lo, hi, palette(i), "");
    curves.line(x, p, palette(i), directions[i].at("direction").get<std::string>(), false);
    for (const auto* values : {&p, &lo, &hi})
      for (double v : *values)
        if (v > 0) highest = std::max(highest, v), lowest = std::min(lowest, v);
  }
  // (A value at a power of ten is that decade's end: no empty decade beyond it.)
  probability_log_axis(curves, highest, lowest);
  curves.hline(acceptable_p, "#000000", fmt::format("acceptable ({:.3g}: one per {} {})", acceptable_p, u.figure(u.area(acceptable_area)), u.area_unit()));
  curves.caption("Beside the path: a person standing at that lateral distance from the mower's centre line while it mows past. Ahead "
                 "and behind: a person on its line whom it approaches no nearer than that distance, or leaves from it. Bands: 95 % "
                 "intervals. Logarithmic scale: a probability below its floor (none seen there: zero) is drawn on the floor.");
  o += "<figure>" + curves.svg() + "</figure>\n";

  o += "<h2>Where objects come down</h2>\n";
  const json& views = result.at("plan_views");
  o += plan_view(views.at("first_landings_per_m2_per_km"), views.at("deck_outline_m"), planes_json, distances, range, "First landings outside the deck",
                 "Objects first coming down", u);
  o += plan_view(views.at("hazardous_impacts_per_m2_per_km"), views.at("deck_outline_m"), planes_json, distances, range,
                 fmt::format("Hazardous ground impacts (at least {} {})", u.figure(u.energy(person_energy)), u.energy_unit()), "Hazardous impacts", u);

  if (!planes_json.empty()) {
    o += "<h2>Planes beside the path</h2>\n";
    const long long passes = field_json.at("passes_per_season").get<long long>();
    HtmlTable planes({"plane", "where", "receptor", fmt::format("crossings per {} mowed", u.mowed()), fmt::format("hazardous per {} mowed (95 %)", u.mowed()),
                      "person standing there: P(struck) in one pass (95 %)",
                      fmt::format("over a season of {} pass{} (95 %): a person there each pass struck at least once; people struck ({:g} a pass)",
                                  passes, passes == 1 ? "" : "es", field_json.at("people_per_pass").get<double>())});
    for (const json& r : planes_json) {
      const bool person = r.contains("p_struck_per_pass");
      const Estimate hazardous = estimate_of(r.at("hazardous_per_km"));
      std::string struck = "-", season = "-";
      if (person) {
        const Estimate p = estimate_of(r.at("p_struck_per_pass")), ps = estimate_of(r.at("p_struck_per_season")),
                       people = estimate_of(r.at("people_struck_per_season"));
        struck = fmt::format("{:.3g} ({:.3g}-{:.3g})", p.value, p.low, p.high);
        season = fmt::format("{:.3g} ({:.3g}-{:.3g}); {:.3g} ({:.3g}-{:.3g})", ps.value, ps.low, ps.high, people.value, people.low, people.high);
      }
      planes.row({escape(r.at("name").get<std::string>()),
                  fmt::format("{} {} {}", r.at("side").get<std::string>(), u.figure(u.length(r.at("distance_m").get<double>())), u.length_unit()),
                  r.at("receptor").get<std::string>(), fmt::format("{:.3g}", u.per_mowed(r.at("crossings_per_km").get<double>())),
                  fmt::format("{:.3g} ({:.3g}-{:.3g})", u.per_mowed(hazardous.value), u.per_mowed(hazardous.low), u.per_mowed(hazardous.high)), struck,
                  season});
    }
    o += planes.html();
    Chart heights("Crossings of each plane by height", fmt::format("height above the ground ({})", u.length_unit()),
                  fmt::format("crossings per {} mowed", u.mowed()));
    // (The bands as the file gives them: its band's width, and as many as it has.)
    double band = 0;
    std::size_t bands = 0;
    for (std::size_t i = 0; i < planes_json.size(); ++i) {
      const json& by_height = planes_json[i].at("crossings_per_km_by_height");
      band = by_height.at("band_m").get<double>(), bands = by_height.at("per_km").size();
      std::vector<double> edges, h;
      for (std::size_t b = 0; b <= bands; ++b) edges.push_back(u.length(static_cast<double>(b) * band));
      for (const json& v : by_height.at("per_km")) h.push_back(u.per_mowed(v.get<double>()));
      heights.bars(edges, h, palette(i), planes_json[i].at("name").get<std::string>());
    }
    heights.caption(fmt::format("Every crossing, hazardous or not, in {:.3g} {} bands (the last: {:.3g} {} and above). A vehicle's hazard is "
                                "the windshield band's; a person's, the band up to their height.",
                                u.length(band), u.length_unit(), u.length(static_cast<double>(bands) * band - band), u.length_unit()));
    o += "<figure>" + heights.svg() + "</figure>\n";
  }

  const json& thrown = result.at("throw");
  o += "<h2>The throw</h2>\n";
  o += fmt::format("<p>Speed off the last blade strike (the speed objects leave with: many are struck again inside the deck, "
                   "faster) {0:.0f} {6} on average (95th percentile {1:.0f} {6}); off the first strike {2:.0f} {6} on average (95th "
                   "percentile {3:.0f} {6}), launch elevation {4:.1f}&deg; on average; {5:.0f} % of the thrown objects first came down outside "
                   "the deck; the farthest ground contact was {7:.0f} {8} from the mower.</p>\n",
                   u.speed(thrown.at("last_strike_speed_m_s").at("mean").get<double>()), u.speed(thrown.at("last_strike_speed_m_s").at("q95").get<double>()),
                   u.speed(thrown.at("exit_speed_m_s").at("mean").get<double>()), u.speed(thrown.at("exit_speed_m_s").at("q95").get<double>()),
                   thrown.at("launch_elevation_deg_mean").get<double>(), 100 * thrown.at("first_landing_outside_deck_share").get<double>(), u.speed_unit(),
                   u.length(thrown.at("farthest_ground_contact_m").get<double>()), u.length_unit());
  {
    Chart reach("How far thrown objects reach", fmt::format("distance from the mower ({})", u.length_unit()), "share of thrown objects beyond it");
    std::vector<double> x, y;
    for (const json& point : thrown.at("reach")) x.push_back(u.length(point.at("distance_m").get<double>())), y.push_back(point.at("share_beyond").get<double>());
    reach.line(x, y, palette(0), "", true);
    reach.caption("Each thrown object's farthest ground contact from the mower (its first landing or a later bounce), every kind "
                  "weighted as the field holds it.");
    o += "<figure>" + reach.svg() + "</figure>\n";
  }
  o += "<h2>Objects simulated</h2>\n";
  std::vector<HtmlCell> kinds_header = {"kind", fmt::format("met per {}", u.mowed()), "share that can reach a blade", "simulated"};
  for (int i = 0; i < field::kObjectFates; ++i) kinds_header.push_back(field::object_fate_name(static_cast<field::ObjectFate>(i)));
  for (const char* h : {"at rest under the deck", "left the square", "a knife rode over", "pushed along by an arm"}) kinds_header.push_back(h);
  HtmlTable kinds(kinds_header);
  for (const json& k : field_json.at("objects")) {
    const json& t = k.at("simulated");
    std::vector<HtmlCell> cells = {escape(k.at("name").get<std::string>()), fmt::format("{:.0f}", u.per_mowed(k.at("met_per_km").get<double>())),
                                      fmt::format("{:.3g}", k.at("share_that_can_reach_a_blade").get<double>()),
                                      fmt::format("{}", t.at("objects").get<std::uint64_t>())};
    for (int i = 0; i < field::kObjectFates; ++i)
      cells.push_back(fmt::format("{}", t.at("fates").at(field::object_fate_name(static_cast<field::ObjectFate>(i))).get<std::uint64_t>()));
    for (const char* key : {"at_rest_under_deck", "left_tallied_square", "objects_a_knife_rode_over", "objects_pushed_along_by_an_arm"})
      cells.push_back(fmt::format("{}", t.at(key).get<std::uint64_t>()));
    kinds.row(cells);
  }
  o += kinds.html();
  o += fmt::format("<p>The tallied square reaches &plusmn;{} {} from the mower.</p>\n", u.figure(u.length(range)), u.length_unit());

  o += "<h2>Assumptions</h2>\n";
  HtmlTable assumptions({"assumption", "source"});
  for (const auto& a : result.at("assumptions")) assumptions.row({escape(a.at("what").get<std::string>()), escape(a.at("source").get<std::string>())});
  o += assumptions.html();
  const auto& p = result.at("provenance");
  o += fmt::format("<section id=\"provenance\"><p class=\"small\">j232 {} ({}), {}; seed {}; {} thread(s), {:.1f} s ({:.0f} objects/s).</p></section>\n", escape(p.at("version").get<std::string>()),
                   escape(p.at("git_revision").get<std::string>()), escape(p.at("date").get<std::string>()), p.at("seed").get<std::uint64_t>(),
                   p.at("threads").get<int>(), p.at("wall_time_s").get<double>(), p.at("objects_per_second").get<double>());
  o += page_foot();
  return o;
}

namespace {
// A compared design's own hazard: its distances each way and P(struck) at its person planes
// (or why there is no assessment).
std::string hazard_of_design_text(const field::FieldDesign& d, const DisplayUnits& u) {
  if (!d.hazard.valid) return fmt::format("  NO HAZARD ASSESSMENT for this design: {}\n", d.hazard.invalid_reason);
  std::string o = "  hazard distance (estimate / conservative):";
  for (const auto& c : d.hazard.directions)
    o += fmt::format(" {} {} / {};", c.direction, distance_words(c, false, d.range, u), distance_words(c, true, d.range, u));
  o.back() = '\n';
  for (const auto& pl : d.hazard.planes)
    if (pl.plane.receptor == scenario::FieldPlaneSpec::Receptor::Person && pl.along_path)
      o += fmt::format("  a person at plane '{}': P(struck) in one pass {:.3g} ({:.3g}-{:.3g})\n", pl.plane.name, pl.probability.value,
                       pl.probability.low, pl.probability.high);
  return o;
}
}  // namespace

json hazard_comparison_json(const field::FieldComparison& c) {
  json designs = json::array();
  for (const auto& d : c.designs) {
    json figures = json::array(), differences = json::array();
    for (const auto& f : d.figures) figures.push_back({{"name", f.name}, {"per_km", estimate_json(f.per_km)}});
    for (const auto& f : d.differences)
      differences.push_back({{"name", f.name}, {"per_km", estimate_json(f.per_km)}, {"objects_differing", f.objects_differing}});
    json dj = {{"file", d.file}, {"title", d.title}, {"figures", figures}};
    if (!d.differences.empty()) dj["minus_first"] = differences;
    dj["valid"] = d.hazard.valid;
    dj["invalid_reason"] = d.hazard.invalid_reason;
    json struck = json::array();
    for (const auto& pl : d.hazard.planes)
      if (pl.plane.receptor == scenario::FieldPlaneSpec::Receptor::Person && pl.along_path)
        struck.push_back({{"plane", pl.plane.name}, {"p_struck_in_one_pass", estimate_json(pl.probability)}});
    dj["hazard_distance"] = hazard_distances_json(d.hazard.directions);
    dj["person_at_plane"] = struck;
    dj["range_m"] = d.range;
    // What the page draws: each direction's curve, against the design's acceptable density
    // and a person's acceptable probability of being struck.
    dj["acceptable_density_per_m2"] = d.hazard.acceptable_density;
    dj["acceptable_probability"] = d.acceptable_probability;
    dj["directions"] = direction_curves_json(d.hazard.directions);
    designs.push_back(dj);
  }
  return {{"kind", "field designs compared (j232 compare)"},
          {"pairing", "common random numbers: object i of every design drawn from the same seed and index, its flight's random "
                      "events keyed by their number; differences judged object by object (normal interval from the paired "
                      "differences); each design's own figures with quasi-Poisson intervals"},
          {"objects", c.objects},
          {"seed", c.seed},
          {"designs", designs},
          {"provenance", {{"wall_time_s", c.wall_seconds}}}};
}

std::string hazard_comparison_csv(const field::FieldComparison& c) {
  std::string o = "design,title,figure,per_km,low,high,minus_first,minus_first_low,minus_first_high,objects_differing\n";
  auto quoted = [](const std::string& t) {
    std::string q = "\"";
    for (char ch : t) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return q + "\"";
  };
  for (std::size_t d = 0; d < c.designs.size(); ++d) {
    const auto& design = c.designs[d];
    for (std::size_t j = 0; j < design.figures.size(); ++j) {
      const auto& f = design.figures[j].per_km;
      o += fmt::format("{},{},{},{:.6g},{:.6g},{:.6g}", d + 1, quoted(design.title), quoted(design.figures[j].name), f.value, f.low, f.high);
      if (d > 0) {
        const auto& x = design.differences[j];
        o += fmt::format(",{:.6g},{:.6g},{:.6g},{}\n", x.per_km.value, x.per_km.low, x.per_km.high, x.objects_differing);
      } else {
        o += ",,,,\n";
      }
    }
  }
  return o;
}

std::string hazard_comparison_text(const field::FieldComparison& c, const DisplayUnits& u) {
  std::string o;
  for (std::size_t d = 0; d < c.designs.size(); ++d) {
    const auto& design = c.designs[d];
    o += fmt::format("{} {}\n", d == 0 ? "reference:" : fmt::format("design {}:", d + 1), design.title);
    for (std::size_t j = 0; j < design.figures.size(); ++j) {
      const auto& f = design.figures[j].per_km;
      o += fmt::format("  {:<58} {:>10.4g} per {} ({:.4g}-{:.4g})", in_units(design.figures[j].name, u), u.per_mowed(f.value), u.mowed(), u.per_mowed(f.low),
                       u.per_mowed(f.high));
      if (d > 0) {
        const auto& x = design.differences[j];
        o += fmt::format("  minus the reference {:+.4g} ({:+.4g} to {:+.4g}; {} objects differ)", u.per_mowed(x.per_km.value),
                         u.per_mowed(x.per_km.low), u.per_mowed(x.per_km.high), x.objects_differing);
      }
      o += "\n";
    }
    o += hazard_of_design_text(design, u);
  }
  return o;
}

namespace {
// A compared design's name on the page.
std::string design_name(std::size_t d, const json& design) {
  return (d == 0 ? "reference: " : fmt::format("design {}: ", d + 1)) + escape(design.at("title").get<std::string>());
}

// Each design's own hazard: a table of its distances and P(struck) at its person planes, and
// per direction a chart of P(struck) against distance with every design's curve.
std::string comparison_hazard_html(const json& designs, const DisplayUnits& u) {
  std::string o = "<h2>Each design's hazard</h2>\n<p>From each design's own run over the same objects, as <code>j232 hazard</code> "
                  "gives it: the hazard distance (hazardous impacts below the acceptable density for good; conservative: on "
                  "the density's 95 % upper bound) and a person's probability of being struck in one pass.</p>\n";
  HtmlTable hazards({"design", "hazard distance (estimate / conservative)", "a person at a plane: P(struck) in one pass (95 %)"});
  for (std::size_t d = 0; d < designs.size(); ++d) {
    const json& design = designs[d];
    if (!design.at("valid").get<bool>()) {
      hazards.row({design_name(d, design), "<strong>no hazard assessment</strong>: " + escape(design.at("invalid_reason").get<std::string>()), ""});
      continue;
    }
    const double range = design.at("range_m").get<double>();
    std::string distances, people;
    for (const json& dir : design.at("hazard_distance"))
      distances += fmt::format("{}: {} / {}<br>", dir.at("direction").get<std::string>(), distance_words(dir, false, range, u),
                               distance_words(dir, true, range, u));
    for (const json& pl : design.at("person_at_plane")) {
      const Estimate p = estimate_of(pl.at("p_struck_in_one_pass"));
      people += fmt::format("'{}': {:.3g} ({:.3g}-{:.3g})<br>", escape(pl.at("plane").get<std::string>()), p.value, p.low, p.high);
    }
    hazards.row({design_name(d, design), distances, people});
  }
  o += hazards.html();
  const json& first = designs.front().at("directions");
  for (std::size_t i = 0; i < first.size(); ++i) {
    Chart chart(fmt::format("Probability of being struck in one pass: {}", first[i].at("direction").get<std::string>()),
                fmt::format("distance from the mower ({})", u.length_unit()), "probability");
    const double acceptable = designs.front().at("acceptable_probability").get<double>();
    double highest = acceptable, lowest = acceptable, far = 5;
    for (const json& design : designs)
      if (i < design.at("directions").size()) {
        const double density = design.at("acceptable_density_per_m2").get<double>();
        for (const json& point : design.at("directions")[i].at("points")) {
          const Estimate exposure = estimate_of(point.at("exposure_per_m2"));
          if (exposure.value > 0 || exposure.high >= density) far = std::max(far, point.at("distance_m").get<double>() + 2);
        }
        far = std::min(far, design.at("range_m").get<double>());
      }
    for (std::size_t d = 0; d < designs.size(); ++d) {
      if (!designs[d].at("valid").get<bool>() || i >= designs[d].at("directions").size()) continue;
      std::vector<double> x, p, lo, hi;
      for (const json& point : designs[d].at("directions")[i].at("points")) {
        if (!(point.at("distance_m").get<double>() <= far)) break;
        const Estimate struck = estimate_of(point.at("p_struck"));
        x.push_back(u.length(point.at("distance_m").get<double>())), p.push_back(struck.value), lo.push_back(struck.low), hi.push_back(struck.high);
      }
      chart.band(x, lo, hi, palette(d), "");
      chart.line(x, p, palette(d), d == 0 ? "reference" : fmt::format("design {}", d + 1), false);
      for (const auto* values : {&p, &lo, &hi})
        for (double v : *values)
          if (v > 0) highest = std::max(highest, v), lowest = std::min(lowest, v);
    }
    probability_log_axis(chart, highest, lowest);
    chart.hline(acceptable, "#000000", fmt::format("acceptable ({:.3g})", acceptable));
    chart.caption(escape(first[i].at("meaning").get<std::string>()) + ". Bands: 95 % intervals; logarithmic scale, zero on the floor.");
    o += "<figure>" + chart.svg() + "</figure>\n";
  }
  return o;
}
}  // namespace

std::string hazard_comparison_html(const json& c, const DisplayUnits& u) {
  const json& designs = c.at("designs");
  if (designs.empty()) throw std::invalid_argument("compare.json: no design to draw");
  std::string o = page_head("Field designs compared");
  o += "<h1>Field designs compared: thrown-object hazard</h1>\n";
  o += fmt::format(
      "<p>{} objects met in turn by every design with common random numbers (seed {}): object i of each design is drawn from the "
      "same seed and index and its flight's random events are keyed by their number, so the differences are judged object by "
      "object. Figures per {} mowed with 95 % intervals (each design: quasi-Poisson; differences: normal, from the paired "
      "differences; the objects whose own counts differ are counted).{}</p>\n",
      c.at("objects").get<std::uint64_t>(), c.at("seed").get<unsigned long long>(), u.mowed(),
      u.us ? " Figures per mile mowed and distances in feet (US customary units); compare.json and compare.csv keep SI units (per km, m)."
           : "");
  std::vector<HtmlCell> header = {"figure"};
  for (std::size_t d = 0; d < designs.size(); ++d) header.push_back(design_name(d, designs[d]));
  HtmlTable figures(header);
  const json& names = designs.front().at("figures");
  for (std::size_t j = 0; j < names.size(); ++j) {
    const std::string name = names[j].at("name").get<std::string>();
    std::vector<HtmlCell> cells = {escape(in_units(name, u)) + (u.us ? " (per mile)" : "")};
    for (std::size_t d = 0; d < designs.size(); ++d) {
      const Estimate f = estimate_of(designs[d].at("figures").at(j).at("per_km"));
      std::string cell = fmt::format("{:.4g} ({:.4g}-{:.4g})", u.per_mowed(f.value), u.per_mowed(f.low), u.per_mowed(f.high));
      if (d > 0) {
        const json& x = designs[d].at("minus_first").at(j);
        const Estimate diff = estimate_of(x.at("per_km"));
        cell += fmt::format("<br><small>minus the reference: {:+.4g} ({:+.4g} to {:+.4g}); {} objects differ</small>", u.per_mowed(diff.value),
                            u.per_mowed(diff.low), u.per_mowed(diff.high), x.at("objects_differing").get<std::uint64_t>());
      }
      cells.push_back(cell);
    }
    figures.row(cells);
  }
  o += figures.html();
  o += comparison_hazard_html(designs, u);
  o += fmt::format("<section id=\"provenance\"><p class=\"small\">{:.1f} s.</p></section>\n", c.at("provenance").at("wall_time_s").get<double>());
  o += page_foot();
  return o;
}

}  // namespace j232::report
