#include "report/scenario_json.hpp"

#include "scenario/ground_kinds.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "assess/tally.hpp"
#include "scene/j232_setup.hpp"
#include "units/quantity.hpp"

namespace j232::report {

namespace {
using json = nlohmann::ordered_json;

json restitution_json(const blade::Restitution& r) {
  if (r.model == blade::Restitution::Model::Constant) return {{"model", "constant"}, {"e", r.e}};
  return {{"model", "power_law"},
          {"coefficient", r.coefficient},
          {"exponent", r.exponent},
          {"maximum", r.maximum},
          {"reference_speed_m_s", r.reference_speed}};
}

json spindle_json(const scenario::SpindleSpec& sp) {
  const auto& b = sp.blade;
  json arms = json::array();
  for (const auto& a : b.arms) {
    json links = json::array();
    for (const auto& l : a.links)
      links.push_back({{"length_m", l.length},
                       {"mass_kg", l.mass},
                       {"centre_of_mass_m", l.centre()},
                       {"inertia_kg_m2", l.inertia()},
                       {"seized", l.seized}});
    arms.push_back({{"azimuth_deg", a.azimuth / units::degree}, {"pivot_radius_m", a.pivot_radius}, {"links", links}});
  }
  return {{"speed_rpm", b.omega / units::rpm},
          {"speed_rad_s", b.omega},
          {"height_m", sp.geometry.height},
          {"thickness_m", sp.geometry.thickness},
          {"edge",
           {{"bevel_angle_deg", sp.geometry.edge.bevel_angle / units::degree},
            {"bevel_side", sp.geometry.edge.bevel_side == scenario::EdgeSpec::Side::Top ? "top" : "bottom"},
            {"width_m", sp.geometry.edge.width},
            {"sail_height_m", sp.geometry.edge.sail_height},
            {"sail_angle_deg", sp.geometry.edge.sail_angle / units::degree},
            {"friction", sp.geometry.edge.friction}}},
          {"mass_kg", b.mass()},
          {"tip_radius_m", b.tip_radius()},
          {"hub",
           {{"bar_mass_kg", b.hub.bar_mass},
            {"bar_length_m", b.hub.bar_length},
            {"bar_mount", b.hub.bar_mount == blade::BarMount::End ? "end" : "centre"},
            {"inertia_kg_m2", b.hub.extra_inertia},
            {"drive_inertia_kg_m2", b.hub.drive_inertia},
            {"drive", b.hub.constant_speed ? "constant_speed" : "free"}}},
          {"arms", arms},
          {"blade_name", sp.blade_name},
          {"x_m", sp.x},
          {"y_m", sp.y},
          {"sense", sp.sense > 0 ? "ccw" : "cw"},
          {"phase_deg", sp.phase ? json(*sp.phase / units::degree) : json("random")}};
}

json guard_json(const scenario::HousingSpec& h, const scenario::GuardSpec& g) {
  json j = {{"name", g.name}};
  if (g.along.empty())
    j.update({{"azimuth_from_deg", g.azimuth.from / units::degree}, {"azimuth_to_deg", g.azimuth.to / units::degree}});
  else
    j.update({{"along_m", g.along}, {"top_m", h.guard_top(g)}});
  j.update({{"kind", g.kind == scenario::GuardSpec::Kind::Flap ? "flap" : "chains"}, {"bottom_m", g.bottom}});
  if (g.kind == scenario::GuardSpec::Kind::Flap)
    j.update({{"thickness_m", g.thickness}, {"density_kg_m3", g.density}, {"panel_width_m", g.panel_width}});
  else
    j.update({{"openness", g.openness}, {"pass_speed_factor", g.pass_speed_factor}});
  j.update({{"restitution", g.restitution}, {"friction", g.friction}});
  return j;
}

json deflector_json(const scenario::DeflectorSpec& d) {
  json j = {{"name", d.name}};
  if (d.along.empty())
    j.update(
        {{"azimuth_from_deg", d.azimuth.from / units::degree}, {"azimuth_to_deg", d.azimuth.to / units::degree}, {"radius_m", d.radius}});
  else
    j.update({{"along_m", d.along}});
  j.update({{"bottom_m", d.bottom}, {"top_m", d.top}});
  return j;
}

json uncertainty_json(const scenario::UncertaintySpec& u) {
  json inputs = json::array();
  for (const auto& in : u.inputs) inputs.push_back({{"parameter", in.parameter}, {"low", in.low}, {"high", in.high}, {"basis", in.basis}});
  return {{"base_draws", u.base_draws},
          {"replicates", u.replicates},
          {"inputs", inputs},
          {"used_by", "j232 uq (not by j232 run); no inputs: the default set of estimated inputs"}};
}

json opening_json(const scenario::HousingSpec& h, const scenario::OpeningSpec& o) {
  json j = {{"name", o.name},
            {"azimuth_from_deg", o.azimuth.from / units::degree},
            {"azimuth_to_deg", o.azimuth.to / units::degree},
            {"top_m", h.opening_top(o)}};
  if (o.chute_length > 0) j.update({{"chute_length_m", o.chute_length}, {"chute_end_top_m", h.chute_end_top(o)}});
  return j;
}

json zone_json(const scenario::OperatorZoneSpec& z) {
  if (z.kind == scenario::OperatorZoneSpec::Kind::Sector)
    return {{"kind", "sector"},
            {"azimuth_from_deg", z.azimuth.from / units::degree},
            {"azimuth_to_deg", z.azimuth.to / units::degree},
            {"bottom_m", z.bottom},
            {"top_m", z.top}};
  return {{"kind", "derived"},
          {"seat_x_m", z.seat_x},
          {"seat_y_m", z.seat_y},
          {"seat_z_m", z.seat_z},
          {"shoulder_height_m", z.shoulder_height},
          {"shoulder_half_width_m", z.shoulder_half_width},
          {"reach_m", z.reach},
          {"knee_height_m", z.knee_height}};
}

json feed_json(const scenario::Scenario& s) {
  const scenario::FeedSpec& f = s.feed;
  json stations = json::array();
  for (const auto& st : s.feed_stations())
    stations.push_back({{"spindle", st.spindle + 1}, {"radius_m", st.radius}, {"azimuth_deg", st.azimuth / units::degree}});
  return {{"nails", f.nails},
          {"stations", stations},
          {"drop_height_m", f.drop_height},
          {"outlet_diameter_m", f.outlet_diameter},
          {"outlet_speed_max_m_s", f.outlet_speed_max},
          {"tilt_max_deg", f.tilt_max / units::degree},
          {"ground_speed_m_s", f.ground_speed}};
}

// A housing mesh replaces the generated deck, its skirt and openings: only what still
// applies is echoed.
json housing_json(const scenario::Scenario& s, bool from_mesh, const std::vector<double>& opening_widths) {
  const scenario::HousingSpec& h = s.housing;
  json guards = json::array(), deflectors = json::array(), openings = json::array();
  for (const auto& g : h.guards) guards.push_back(guard_json(h, g));
  for (const auto& d : h.deflectors) deflectors.push_back(deflector_json(d));
  for (std::size_t i = 0; i < h.openings.size(); ++i) {
    openings.push_back(opening_json(h, h.openings[i]));
    if (i < opening_widths.size()) openings.back()["width_m"] = opening_widths[i];  // as cut, along the outline
  }
  if (from_mesh)
    return {{"generated", false},
            {"restitution", restitution_json(h.restitution)},
            {"friction", h.friction},
            {"guards", guards},
            {"deflectors", deflectors}};
  return {{"generated", true},
          {"deck_radius_m", s.deck_radius()},
          {"margin_m", h.margin},
          {"openings", openings},
          {"skirt_bottom_m", h.skirt_bottom},
          {"skirt_depth_m", h.skirt_depth},
          {"deck_top_m", h.plate_height()},
          {"restitution", restitution_json(h.restitution)},
          {"friction", h.friction},
          {"guards", guards},
          {"deflectors", deflectors}};
}

json target_json(const scenario::Scenario& s, bool from_mesh) {
  if (from_mesh) return {{"generated", false}};
  if (s.target.shape == scenario::TargetSpec::Shape::Outline)
    return {{"generated", true},        {"shape", "outline"}, {"distance_m", s.target.distance}, {"farthest_m", scene::target_radius(s)},
            {"bottom_m", s.target.bottom}, {"top_m", s.target_top()}, {"segments", s.target.segments}};
  return {{"generated", true},           {"shape", "circle"},     {"distance_m", s.target.distance}, {"radius_m", s.reach() + s.target.distance},
          {"bottom_m", s.target.bottom}, {"top_m", s.target_top()}, {"segments", s.target.segments}};
}

json criteria_json(const scenario::CriteriaSpec& c) {
  json j;
  for (int k = 0; k < assess::kCategories; ++k) j[assess::category_name(k)] = assess::category_limit(c, k);
  j["denominator"] = c.denominator == scenario::CriteriaSpec::Denominator::Marks ? "marks" : "nails_fed";
  j["required_pass_probability"] = c.required_pass_probability;
  return j;
}

const char* estimator_name(scenario::RunSpec::Estimator e) {
  switch (e) {
    case scenario::RunSpec::Estimator::Replicates: return "replicates";
    case scenario::RunSpec::Estimator::EveryNail: return "every_nail";
    case scenario::RunSpec::Estimator::Narrower: break;
  }
  return "narrower";
}

json run_json(const scenario::Scenario& s) {
  const scenario::RunSpec& r = s.run;
  return {{"replicates", r.replicates},
          {"seed", r.seed},
          {"estimator", estimator_name(r.estimator)},
          {"target_half_width", r.target_half_width ? json(*r.target_half_width) : json(nullptr)},
          {"until_settled", r.until_settled},
          {"max_replicates", r.max_replicates},
          {"chord_tolerance_m", r.chord_tolerance},
          {"time_limit_s", s.time_limit()},
          {"max_bounces", s.max_bounces()},
          {"max_gentle_contacts", r.max_gentle_contacts},
          {"max_strikes", s.max_strikes()},
          {"max_contacts_per_pass", r.max_contacts_per_pass},
          {"rest_speed_m_s", r.rest_speed},
          {"contact_search", r.reference_contact_search ? "fixed_steps" : "advancement"},
          {"restitution_law", r.restitution_law == scenario::RestitutionLaw::Poisson ? "poisson" : "energetic"},
          {"contacts", r.contact_model == scenario::ContactModel::Simultaneous ? "simultaneous" : "sequential"},
          {"blade_push", r.blade_push == scenario::BladePush::Held ? "held" : "impacts"}};
}

}  // namespace

nlohmann::ordered_json scenario_json(const scenario::Scenario& s) {
  json spindles = json::array(), meshes = json::array();
  for (const auto& sp : s.spindles) spindles.push_back(spindle_json(sp));
  for (const auto& m : s.meshes) meshes.push_back({{"path", m.path}, {"label", scenario::mesh_label_name(m.label)}, {"scale", m.scale}});
  const scene::MeshRoles roles = scene::mesh_roles(s);
  json j = {
      {"file", s.file},
      {"title", s.title},
      {"spindles", spindles},
      {"restitution", restitution_json(s.restitution)},
      {"nail",
       {{"length_m", s.nail.length},
        {"diameter_m", s.nail.diameter},
        {"mass_kg", s.nail.mass},
        {"length_tolerance_m", s.nail.length_tolerance},
        {"mass_tolerance_kg", s.nail.mass_tolerance}}},
      {"feed", feed_json(s)},
      {"housing", housing_json(s, roles.housing, scene::opening_widths(s))},
      {"ground",
       {{"restitution", s.ground.restitution},
        {"angle_exponent", s.ground.angle_exponent},
        {"max_restitution", s.ground.max_restitution},
        {"friction", s.ground.friction},
        {"roughness_deg", s.ground.roughness / units::degree}}},
      {"target", target_json(s, roles.target)},
      {"meshes", meshes},
      {"operator_zone", zone_json(s.zone)},
      {"board", {{"puncture_energy_per_width_J_m", s.board.puncture_energy_per_width}, {"hit_fraction", s.board.hit_fraction}, {"crush_depth_m", s.board.crush_depth}}},
      {"criteria", criteria_json(s.criteria)},
      {"air", {{"drag", s.air.drag}, {"density_kg_m3", s.air.density}, {"cd_normal", s.air.cd_normal}, {"cd_axial", s.air.cd_axial}, {"spin_average", s.air.spin_average}}},
      {"uncertainty", uncertainty_json(s.uncertainty)},
      {"run", run_json(s)},
  };
  if (s.field.present) j["ground"]["rolling_resistance"] = s.ground.rolling_resistance;  // round objects roll on it (nails do not)
  // (The default kind, turf, with nothing sinking in, is the earlier releases' ground: named
  // only when it is another, so that results of the same physics read the same.)
  if (s.ground.kind != "turf") j["ground"]["kind"] = s.ground.kind;
  if (s.ground.penetrability > 0) j["ground"]["penetrability"] = s.ground.penetrability;
  return j;
}

std::vector<Assumption> assumptions(const scenario::Scenario& s) {
  std::vector<Assumption> a;
  const char* params = "docs/model.md §8";
  a.push_back(
      {"Impact: impulse-momentum model of the blade (hub + pinned links); the nail a rigid capsule struck where the blade's edge, "
       "bevel, faces or sail first touch it (continuous contact search), along the geometric normal there, with Coulomb friction "
       "(stick or slip) and restitution checked to create no energy; every contact of a pass is resolved; the blade is back at "
       "speed and radially aligned between passes",
       "report 445-1 Ch. 2, generalised (docs/model.md §5.1)"});
  a.push_back({fmt::format("Nail-on-blade restitution: {}", s.restitution.model == blade::Restitution::Model::Constant
                                                                ? fmt::format("e = {:g}", s.restitution.e)
                                                                : std::string("e(v) power law")),
               "report 445-1 (0.3-0.9); Johnson, Contact Mechanics 11.4 for e(v)"});
  for (std::size_t k = 0; k < s.spindles.size(); ++k) {
    const auto& sp = s.spindles[k];
    const auto& e = sp.geometry.edge;
    bool same_as_earlier = false;
    for (std::size_t j = 0; j < k; ++j) {
      const auto& o = s.spindles[j].geometry;
      same_as_earlier |= o.thickness == sp.geometry.thickness && o.edge.bevel_angle == e.bevel_angle &&
                         o.edge.bevel_side == e.bevel_side && o.edge.width == e.width && o.edge.sail_height == e.sail_height &&
                         o.edge.sail_angle == e.sail_angle && o.edge.friction == e.friction;
    }
    if (same_as_earlier) continue;
    const std::string which = s.spindles.size() == 1 ? "Blade edge" : fmt::format("Blade edge (spindle {})", k + 1);
    // (In a field each object kind has its own friction on the blade, stated with the kind.)
    a.push_back({fmt::format("{}: {:.1f} mm plate, {:g} deg bevel on the {} face, {:.0f} mm wide, {}; {}", which,
                             sp.geometry.thickness * 1e3, e.bevel_angle / units::degree,
                             e.bevel_side == scenario::EdgeSpec::Side::Top ? "top" : "bottom", e.width * 1e3,
                             e.sail_height > 0 ? fmt::format("a {:.0f} mm sail at {:g} deg", e.sail_height * 1e3, e.sail_angle / units::degree)
                                               : std::string("no sail"),
                             s.field.present ? std::string("each object kind's own friction on it")
                                             : fmt::format("nail-on-blade friction {:g}", e.friction)),
                 fmt::format("{} (estimates: mower blades are ground to about 30 deg; friction steel on steel, handbook 0.42-0.57 "
                             "kinetic; no figure for industrial cutters)",
                             params)});
  }
  a.push_back({fmt::format("Nail: {:.1f} mm long, {:.2f} mm shank, {:.2f} g +/- {:.2f} g", s.nail.length * 1e3, s.nail.diameter * 1e3,
                           s.nail.mass * 1e3, s.nail.mass_tolerance * 1e3),
               fmt::format("{} (6d box nail)", params)});
  a.push_back({fmt::format("Feed: {} nails, dropped {:.0f} mm onto the blade at {} station(s), upright within {:.0f} deg", s.feed.nails,
                           s.feed.drop_height * 1e3, s.feed_station_count(), s.feed.tilt_max * 180 / units::pi),
               "estimate: SAE J232 feed geometry not available (docs/model.md 5.1)"});
  a.push_back({fmt::format("Board: puncture at {:g} J/m of the width the nail presses on it (its part within {:g} mm of the "
                           "first touch), hit at {:g} of that; the energy a plastic impact takes out at the point that strikes",
                           s.board.puncture_energy_per_width, s.board.crush_depth * 1e3, s.board.hit_fraction),
               fmt::format("{} (estimate: no published value for 350# double-wall)", params)});
  if (scene::mesh_roles(s).target)
    a.push_back({"Target board: the scenario's target mesh(es)", "scenario (user geometry)"});
  else
    a.push_back({fmt::format("Target {} {:.0f} mm outside {}, {:.0f} to {:.0f} mm above ground",
                             s.target.shape == scenario::TargetSpec::Shape::Outline ? "board following the deck" : "ring about the deck's centre",
                             s.target.distance * 1e3,
                             s.target.shape == scenario::TargetSpec::Shape::Outline ? "every tip circle" : "the farthest tip",
                             s.target.bottom * 1e3, s.target_top() * 1e3),
                 fmt::format("{} (ANSI B71.1 enclosure wording as stand-in)", params)});
  if (scene::mesh_roles(s).housing) {
    a.push_back({"Deck and skirt: the scenario's mesh(es)", "scenario (user geometry)"});
  } else {
    std::string deck = fmt::format("Deck: skirt from {:.0f} mm to {:.0f} mm above ground", s.housing.skirt_bottom * 1e3,
                                   s.housing.plate_height() * 1e3);
    const auto widths = scene::opening_widths(s);
    for (std::size_t i = 0; i < s.housing.openings.size(); ++i) {
      const auto& o = s.housing.openings[i];
      deck += fmt::format("; opening '{}' {:g} to {:g} deg up to {:.0f} mm, {:.0f} mm wide as cut along the outline", o.name,
                          o.azimuth.from / units::degree, o.azimuth.to / units::degree, s.housing.opening_top(o) * 1e3, widths[i] * 1e3);
    }
    a.push_back({deck, "scenario"});
  }
  for (const auto& e : s.estimates) {
    const bool quoted = e.value.size() >= 2 && e.value.front() == '"' && e.value.back() == '"';
    a.push_back({fmt::format("{} = {}", e.key, quoted ? e.value.substr(1, e.value.size() - 2) : e.value), "the scenario's author: an estimate"});
  }
  for (const auto& name : s.housing.absent_guards)
    a.push_back({fmt::format("Guard '{}' is described but not fitted (present = false): nails meet no guard there", name), "scenario"});
  // Every guard with every parameter the flight uses, given or default.
  for (const auto& g : s.housing.guards) {
    if (g.kind == scenario::GuardSpec::Kind::Flap) {
      const auto f = scene::flap_geometry(s, g);
      const double width = f.swinging;
      a.push_back({fmt::format("Flap '{}': a plate hinged {:.0f} mm above ground, down to {:.0f} mm, {:.0f} mm wide swinging as one; "
                               "{:.1f} mm thick at {:g} kg/m3 ({:.3f} kg); restitution {:g}, friction {:g}; taken at rest at each "
                               "impact (swung back between contacts); {} do not pass it",
                               g.name, f.hinge * 1e3, f.bottom * 1e3, width * 1e3, g.thickness * 1e3, g.density,
                               g.density * g.thickness * width * (f.hinge - f.bottom), g.restitution, g.friction,
                               s.field.present ? "objects" : "nails"),
                   "scenario, or estimates where not given (belting 6 mm, 1200 kg/m3)"});
      continue;
    }
    a.push_back({fmt::format("Guard '{}' ({}): {:.0f} to {:.0f} mm above ground; {} pass between its links with probability "
                             "{:g}, keeping {:g} of their speed; restitution {:g}, friction {:g}",
                             g.name,
                             g.along.empty() ? fmt::format("below the skirt from {:g} to {:g} deg", g.azimuth.from / units::degree,
                                                           g.azimuth.to / units::degree)
                                             : fmt::format("along a {}-point polyline", g.along.size()),
                             g.bottom * 1e3, (g.along.empty() ? s.housing.skirt_bottom : s.housing.guard_top(g)) * 1e3, s.field.present ? "objects" : "nails",
                             g.openness, g.pass_speed_factor,
                             g.restitution, g.friction),
                 "scenario, or estimates where not given (openness, speed kept: no published chain-curtain figures)"});
  }
  a.push_back({s.zone.kind == scenario::OperatorZoneSpec::Kind::Sector
                   ? std::string("Operator zone: explicit sector of the board")
                   : fmt::format("Operator zone: board seen from the blade toward the 95th-percentile reach envelope of "
                                 "an operator seated at ({:.2f}, {:.2f}, {:.2f}) m",
                                 s.zone.seat_x, s.zone.seat_y, s.zone.seat_z),
               fmt::format("{} (MIL-STD-1472G reach values)", params)});
  a.push_back({s.ground.angle_exponent == 0
                   ? fmt::format("Ground: restitution {:g} at any angle, friction {:g}, roughness {:.0f} deg", s.ground.restitution,
                                 s.ground.friction, s.ground.roughness / units::degree)
                   : fmt::format("Ground: normal restitution {:g} x (impact angle / 90 deg)^-{:g} (at most {:g}), friction {:g}, "
                                 "roughness {:.0f} deg",
                                 s.ground.restitution, s.ground.angle_exponent, s.ground.max_restitution, s.ground.friction,
                                 s.ground.roughness / units::degree),
               s.ground.kind == "turf" ? fmt::format("{} (turf: value an estimate; angle law from rockfall data, Wyllie 2014)", params)
                                       : fmt::format("{} ([ground] kind = \"{}\": {}; angle law from rockfall data, Wyllie 2014)", params,
                                                     s.ground.kind, scenario::ground_kind(s.ground.kind)->basis)});
  if (s.ground.penetrability > 0)
    a.push_back({fmt::format("A nail meeting the ground point-first (at an end, within 45 deg of square on) sinks in by Young's "
                             "penetration equation, penetrability S {:g}, and stays when that is deeper than two shank diameters",
                             s.ground.penetrability),
                 "Young 1997 (SAND97-2426), extrapolated from penetrators of kilograms to a 2 g nail: an estimate (docs/model.md §5.3a)"});
  a.push_back({!s.air.drag      ? std::string(s.field.present ? "Air drag off (conservative: faster objects)" : "Air drag off (conservative: faster nails)")
               : s.field.present ? fmt::format("Air drag on: rho {:g} kg/m3; each object a sphere with its kind's drag coefficient on its "
                                               "cross-section",
                                               s.air.density)
                                 : fmt::format("Air drag on: Cd {:g} cross-flow, {:g} end-on, rho {:g} kg/m3; {}", s.air.cd_normal, s.air.cd_axial,
                                               s.air.density,
                                               s.air.spin_average ? "averaged over the axis's turn for a fast-spinning nail"
                                                                  : "as the axis stands, in steps of at most 0.3 rad of its turn (reference)") +
                                       "; the tumbling slowed by the cross-flow drag on the turning shank (strip theory, estimate)",
               fmt::format("{} (handbook)", params)});
  a.push_back({s.criteria.denominator == scenario::CriteriaSpec::Denominator::NailsFed
                   ? std::string("Shares are of the nails fed")
                   : std::string("Shares are of all marks (the report's literal wording)"),
               "docs/model.md 5.6 (the report's wording read two ways)"});
  a.push_back({fmt::format("Verdict: passes when P(pass) >= {:g}", s.criteria.required_pass_probability),
               "program default (not part of SAE J232)"});
  return a;
}

}  // namespace j232::report
