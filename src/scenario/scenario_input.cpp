// Reads a J232 assessment scenario (scenario.hpp) from TOML. Every key is optional
// except the blade; each default is the documented one (docs/model.md).
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fmt/format.h>

#include "scenario/blade_input.hpp"
#include "scenario/impact_input.hpp"
#include "scenario/scenario.hpp"
#include "scenario/toml_reader.hpp"

namespace j232::scenario {

using units::Kind;

namespace {

constexpr double kDegree = units::pi / 180.0;

void read_nail(const TableReader& t, NailSpec& n) {
  n.length = t.quantity_or("length", Kind::Length, n.length, Range::Positive);
  n.diameter = t.quantity_or("diameter", Kind::Length, n.diameter, Range::Positive);
  n.head_diameter = t.quantity_or("head_diameter", Kind::Length, n.head_diameter, Range::Positive);
  n.mass = t.quantity_or("mass", Kind::Mass, n.mass, Range::Positive);
  n.length_tolerance = t.quantity_or("length_tolerance", Kind::Length, n.length_tolerance, Range::NonNegative);
  n.mass_tolerance = t.quantity_or("mass_tolerance", Kind::Mass, n.mass_tolerance, Range::NonNegative);
  if (n.length_tolerance >= n.length) throw t.error("length_tolerance", "expected a tolerance smaller than the length");
  if (n.mass_tolerance >= n.mass) throw t.error("mass_tolerance", "expected a tolerance smaller than the mass");
  if (n.diameter >= n.length) throw t.error("diameter", "expected a nail thinner than it is long");
  t.refuse_unknown_keys();
}

void read_feed(const TableReader& t, FeedSpec& f) {
  f.nails = static_cast<int>(t.integer_or("nails", f.nails, 1, 100000));
  f.drop_height = t.quantity_or("drop_height", Kind::Length, f.drop_height, Range::NonNegative);
  f.outlet_diameter = t.quantity_or("outlet_diameter", Kind::Length, f.outlet_diameter, Range::NonNegative);
  f.outlet_speed_max = t.quantity_or("outlet_speed_max", Kind::Speed, f.outlet_speed_max, Range::NonNegative);
  f.tilt_max = t.quantity_or("tilt_max", Kind::Angle, f.tilt_max, Range::NonNegative);
  if (f.tilt_max > 60 * kDegree) throw t.error("tilt_max", "expected at most 60 deg: the nail drops through a tube");
  f.ground_speed = t.quantity_or("ground_speed", Kind::Speed, f.ground_speed, Range::NonNegative);
  for (const auto& s : t.array_of_tables("stations")) {
    FeedStation st;
    st.radius = s.quantity("radius", Kind::Length, Range::NonNegative);
    st.azimuth = s.quantity_or("azimuth", Kind::Angle, 0.0);
    s.refuse_unknown_keys();
    f.stations.push_back(st);
  }
  t.refuse_unknown_keys();
}

void read_guard(const TableReader& t, GuardSpec& g, bool with_geometry) {
  g.name = t.string_or("name", g.name, {});
  if (with_geometry) {
    g.azimuth_from = t.quantity("azimuth_from", Kind::Angle);
    g.azimuth_to = t.quantity("azimuth_to", Kind::Angle);
    g.bottom = t.quantity_or("bottom", Kind::Length, g.bottom, Range::NonNegative);
  }
  g.openness = t.quantity_or("openness", Kind::Dimensionless, g.openness, Range::UnitInterval);
  g.pass_speed_factor = t.quantity_or("pass_speed_factor", Kind::Dimensionless, g.pass_speed_factor, Range::UnitInterval);
  g.restitution = t.quantity_or("restitution", Kind::Dimensionless, g.restitution, Range::UnitInterval);
  g.friction = t.quantity_or("friction", Kind::Dimensionless, g.friction, Range::NonNegative);
}

void read_housing(const TableReader& t, HousingSpec& h) {
  h.deck_radius = t.quantity_or("deck_radius", Kind::Length, h.deck_radius, Range::Positive);
  h.skirt_bottom = t.quantity_or("skirt_bottom", Kind::Length, h.skirt_bottom, Range::NonNegative);
  h.skirt_depth = t.quantity_or("skirt_depth", Kind::Length, h.skirt_depth, Range::Positive);
  h.friction = t.quantity_or("friction", Kind::Dimensionless, h.friction, Range::NonNegative);
  if (auto r = t.table("restitution")) h.restitution = read_restitution(*r);
  for (const auto& g : t.array_of_tables("guards")) {
    GuardSpec guard;
    read_guard(g, guard, true);
    if (guard.bottom >= h.skirt_bottom)
      throw g.error("bottom", fmt::format("expected the curtain's lower edge below the skirt bottom ({} m)", h.skirt_bottom));
    g.refuse_unknown_keys();
    h.guards.push_back(guard);
  }
  for (const auto& d : t.array_of_tables("deflectors")) {
    DeflectorSpec def;
    def.name = d.string_or("name", def.name, {});
    def.azimuth_from = d.quantity("azimuth_from", Kind::Angle);
    def.azimuth_to = d.quantity("azimuth_to", Kind::Angle);
    def.radius = d.quantity("radius", Kind::Length, Range::Positive);
    def.bottom = d.quantity("bottom", Kind::Length, Range::NonNegative);
    def.top = d.quantity("top", Kind::Length, Range::Positive);
    if (def.top <= def.bottom) throw d.error("top", "expected the top above the bottom");
    d.refuse_unknown_keys();
    h.deflectors.push_back(def);
  }
  t.refuse_unknown_keys();
}

void read_zone(const TableReader& t, OperatorZoneSpec& z) {
  const std::string kind = t.string_or("kind", "derived", {"derived", "sector"});
  if (kind == "sector") {
    z.kind = OperatorZoneSpec::Kind::Sector;
    z.azimuth_from = t.quantity("azimuth_from", Kind::Angle);
    z.azimuth_to = t.quantity("azimuth_to", Kind::Angle);
    z.bottom = t.quantity_or("bottom", Kind::Length, 0.0, Range::NonNegative);
    z.top = t.quantity("top", Kind::Length, Range::Positive);
    if (z.top <= z.bottom) throw t.error("top", "expected the top above the bottom");
  } else {
    z.kind = OperatorZoneSpec::Kind::Derived;
    z.seat_x = t.quantity_or("seat_x", Kind::Length, z.seat_x);
    z.seat_y = t.quantity_or("seat_y", Kind::Length, z.seat_y);
    z.seat_z = t.quantity_or("seat_z", Kind::Length, z.seat_z, Range::NonNegative);
    z.shoulder_height = t.quantity_or("shoulder_height", Kind::Length, z.shoulder_height, Range::Positive);
    z.shoulder_half_width = t.quantity_or("shoulder_half_width", Kind::Length, z.shoulder_half_width, Range::NonNegative);
    z.reach = t.quantity_or("reach", Kind::Length, z.reach, Range::Positive);
    z.knee_height = t.quantity_or("knee_height", Kind::Length, z.knee_height, Range::Positive);
  }
  t.refuse_unknown_keys();
}

void read_criteria(const TableReader& t, CriteriaSpec& c) {
  c.hits_zone = t.quantity_or("hits_zone", Kind::Dimensionless, c.hits_zone, Range::UnitInterval);
  c.punctures_zone = t.quantity_or("punctures_zone", Kind::Dimensionless, c.punctures_zone, Range::UnitInterval);
  c.hits_outside = t.quantity_or("hits_outside", Kind::Dimensionless, c.hits_outside, Range::UnitInterval);
  c.punctures_outside = t.quantity_or("punctures_outside", Kind::Dimensionless, c.punctures_outside, Range::UnitInterval);
  c.denominator = t.string_or("denominator", "nails_fed", {"nails_fed", "marks"}) == "marks"
                      ? CriteriaSpec::Denominator::Marks
                      : CriteriaSpec::Denominator::NailsFed;
  c.required_pass_probability =
      t.quantity_or("required_pass_probability", Kind::Dimensionless, c.required_pass_probability, Range::UnitInterval);
  t.refuse_unknown_keys();
}

void read_run(const TableReader& t, RunSpec& r) {
  r.replicates = t.integer_or("replicates", r.replicates, 1, 100'000'000);
  r.seed = static_cast<unsigned long long>(t.integer_or("seed", static_cast<long long>(r.seed), 0, INT64_MAX));
  r.threads = static_cast<int>(t.integer_or("threads", r.threads, 0, 1024));
  r.target_half_width = t.optional_quantity("target_half_width", Kind::Dimensionless, Range::UnitInterval);
  r.max_replicates = t.integer_or("max_replicates", r.max_replicates, 1, 100'000'000);
  r.chord_tolerance = t.quantity_or("chord_tolerance", Kind::Length, r.chord_tolerance, Range::Positive);
  r.time_limit = t.quantity_or("time_limit", Kind::Time, r.time_limit, Range::Positive);
  r.max_bounces = static_cast<int>(t.integer_or("max_bounces", r.max_bounces, 0, 10000));
  r.rest_speed = t.quantity_or("rest_speed", Kind::Speed, r.rest_speed, Range::Positive);
  t.refuse_unknown_keys();
}

const std::vector<std::string> kMeshLabels = {"ground", "housing", "deflector", "guard", "target", "operator_zone"};

}  // namespace

Scenario read_scenario(const std::string& file) { return read_scenario(parse_toml_file(file), file); }

Scenario read_scenario(const toml::table& document, const std::string& file) {
  TableReader root(document, file, "");
  Scenario s;
  s.file = file;
  s.title = root.string_or("title", std::filesystem::path(file).stem().string(), {});

  auto blade_table = root.table("blade");
  if (!blade_table) throw root.error("blade", "missing; expected a [blade] table");
  s.blade = read_blade(*blade_table);
  s.geometry.height = blade_table->quantity_or("height", Kind::Length, s.geometry.height, Range::Positive);
  s.geometry.thickness = blade_table->quantity_or("thickness", Kind::Length, s.geometry.thickness, Range::Positive);
  s.geometry.lift_angle = blade_table->quantity_or("lift_angle", Kind::Angle, s.geometry.lift_angle);
  if (std::abs(s.geometry.lift_angle) > 45 * kDegree) throw blade_table->error("lift_angle", "expected within +/-45 deg");
  blade_table->refuse_unknown_keys();
  const double tip = s.blade.tip_radius();

  if (auto r = root.table("restitution")) s.restitution = read_restitution(*r);
  if (auto n = root.table("nail")) read_nail(*n, s.nail);
  if (auto f = root.table("feed")) read_feed(*f, s.feed);
  if (s.feed.stations.empty()) s.feed.stations.push_back({std::max(0.0, tip - 0.0508), 0.0});

  s.housing.deck_radius = tip + 0.050;
  if (auto h = root.table("housing")) read_housing(*h, s.housing);
  if (s.housing.deck_radius <= tip)
    throw root.table("housing")->error("deck_radius", fmt::format("expected a deck wider than the blade's tip circle ({:.4g} m)", tip));

  if (auto g = root.table("ground")) {
    s.ground.restitution = g->quantity_or("restitution", Kind::Dimensionless, s.ground.restitution, Range::UnitInterval);
    s.ground.friction = g->quantity_or("friction", Kind::Dimensionless, s.ground.friction, Range::NonNegative);
    s.ground.roughness = g->quantity_or("roughness", Kind::Angle, s.ground.roughness, Range::NonNegative);
    g->refuse_unknown_keys();
  }

  s.target.top = s.geometry.height + 0.610;
  if (auto t = root.table("target")) {
    s.target.distance = t->quantity_or("distance", Kind::Length, s.target.distance, Range::Positive);
    s.target.bottom = t->quantity_or("bottom", Kind::Length, s.target.bottom, Range::NonNegative);
    s.target.top = t->quantity_or("top", Kind::Length, s.target.top, Range::Positive);
    s.target.segments = static_cast<int>(t->integer_or("segments", s.target.segments, 16, 100000));
    if (s.target.top <= s.target.bottom) throw t->error("top", "expected the board's top above its bottom");
    if (tip + s.target.distance <= s.housing.deck_radius)
      throw t->error("distance", "expected the board outside the mower deck");
    t->refuse_unknown_keys();
  }

  const auto base = std::filesystem::path(file).parent_path();
  for (const auto& m : root.array_of_tables("meshes")) {
    MeshFile mesh;
    const std::string path = m.string_or("path", "", {});
    if (path.empty()) throw m.error("path", "missing; expected the mesh file's path (OBJ, OFF, PLY or STL)");
    mesh.path = (base / path).string();
    mesh.label = m.string_or("label", "", kMeshLabels);
    if (mesh.label.empty()) throw m.error("label", "missing; expected one of ground, housing, deflector, guard, target, operator_zone");
    mesh.scale = m.quantity_or("scale", Kind::Dimensionless, 1.0, Range::Positive);
    if (mesh.label == "guard") read_guard(m, mesh.guard, false);
    m.refuse_unknown_keys();
    s.meshes.push_back(mesh);
  }

  if (auto z = root.table("operator_zone")) read_zone(*z, s.zone);
  if (auto b = root.table("board")) {
    s.board.puncture_energy_per_width =
        b->quantity_or("puncture_energy_per_width", Kind::EnergyPerLength, s.board.puncture_energy_per_width, Range::Positive);
    s.board.hit_fraction = b->quantity_or("hit_fraction", Kind::Dimensionless, s.board.hit_fraction, Range::UnitInterval);
    b->refuse_unknown_keys();
  }
  if (auto c = root.table("criteria")) read_criteria(*c, s.criteria);
  if (auto a = root.table("air")) {
    s.air.drag = a->boolean_or("drag", s.air.drag);
    s.air.density = a->quantity_or("density", Kind::Density, s.air.density, Range::NonNegative);
    s.air.cd_normal = a->quantity_or("cd_normal", Kind::Dimensionless, s.air.cd_normal, Range::NonNegative);
    s.air.cd_axial = a->quantity_or("cd_axial", Kind::Dimensionless, s.air.cd_axial, Range::NonNegative);
    a->refuse_unknown_keys();
  }
  if (auto r = root.table("run")) read_run(*r, s.run);
  root.refuse_unknown_keys();
  return s;
}

}  // namespace j232::scenario
