// Reads a J232 assessment scenario (scenario.hpp) from TOML (scenario_reader.hpp). Every key is optional
// except the blade; each default is the documented one (docs/model.md).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <set>
#include <fmt/format.h>

#include "scenario/blade_input.hpp"
#include "scenario/ground_kinds.hpp"
#include "scenario/impact_input.hpp"
#include "scenario/scenario.hpp"
#include "scenario/scenario_reader.hpp"
#include "scenario/toml_reader.hpp"
#include "units/arc.hpp"

namespace j232::scenario {

using units::Kind;

namespace {

// Azimuths may be written beyond one turn ("-90 deg", "450 deg"), but not absurdly so.
constexpr Range kAnyAzimuth = Range::between(-4 * units::pi, 4 * units::pi);

void read_nail(const TableReader& t, NailSpec& n) {
  // Plausible for any nail or similar small object a J232-like test could drop.
  n.length = t.quantity_or("length", Kind::Length, n.length, Range::between(0.005, 0.3));
  n.diameter = t.quantity_or("diameter", Kind::Length, n.diameter, Range::between(0.0003, 0.03));
  n.mass = t.quantity_or("mass", Kind::Mass, n.mass, Range::between(1e-5, 1.0));
  n.length_tolerance = t.quantity_or("length_tolerance", Kind::Length, n.length_tolerance, Range::NonNegative);
  n.mass_tolerance = t.quantity_or("mass_tolerance", Kind::Mass, n.mass_tolerance, Range::NonNegative);
  if (n.length_tolerance >= n.length) throw t.error("length_tolerance", "expected a tolerance smaller than the length");
  if (n.mass_tolerance >= n.mass) throw t.error("mass_tolerance", "expected a tolerance smaller than the mass");
  // Its mass over its rod's volume: from wood to the densest metal, or the three values
  // describe no object (a 20 mm rod of 1 g, a pin of 1 kg).
  const double density = n.mass / (0.25 * units::pi * n.diameter * n.diameter * n.length);
  if (!(density >= 500 && density <= 25000)) {
    const char* key = t.has("mass") ? "mass" : t.has("diameter") ? "diameter" : "length";
    throw t.error(key, fmt::format("gives a rod {:.4g} m long and {:.4g} m thick a density of {:.4g} kg/m^3; expected 500 to "
                                   "25000 kg/m^3 (wood to the densest metal): check the mass and the dimensions together",
                                   n.length, n.diameter, density));
  }
  if (n.diameter >= n.length) throw t.error("diameter", "expected a nail thinner than it is long");
  t.refuse_unknown_keys();
}

void read_feed(const TableReader& t, FeedSpec& f, const std::vector<SpindleSpec>& spindles) {
  f.nails = static_cast<int>(t.integer_or("nails", f.nails, 1, 100000));
  f.drop_height = t.quantity_or("drop_height", Kind::Length, f.drop_height, Range::between(0, 3));
  f.outlet_diameter = t.quantity_or("outlet_diameter", Kind::Length, f.outlet_diameter, Range::between(0, 0.3));
  f.outlet_speed_max = t.quantity_or("outlet_speed_max", Kind::Speed, f.outlet_speed_max, Range::between(0, 10));
  f.tilt_max = t.quantity_or("tilt_max", Kind::Angle, f.tilt_max, Range::NonNegative);
  if (f.tilt_max > 60 * units::degree) throw t.error("tilt_max", "expected at most 60 deg: the nail drops through a tube");
  f.ground_speed = t.quantity_or("ground_speed", Kind::Speed, f.ground_speed, Range::between(0, 15));
  for (const auto& s : t.array_of_tables("stations", 360)) {
    FeedStation st;
    st.spindle = static_cast<std::size_t>(s.integer_or("spindle", 1, 1, static_cast<long long>(spindles.size())) - 1);
    // A station outside the tip circle feeds nails the blade can never strike.
    st.radius = s.quantity("radius", Kind::Length, Range::between(0, spindles[st.spindle].blade.tip_radius()));
    st.azimuth = s.quantity_or("azimuth", Kind::Angle, 0.0, kAnyAzimuth);
    s.refuse_unknown_keys();
    if (!f.stations) f.stations.emplace();
    f.stations->push_back(st);
  }
  t.refuse_unknown_keys();
}

// Plan coordinates of parts placed by polyline: within the 100 m scene.
constexpr Range kPlanCoordinate = Range::between(-50, 50);

// An arc of azimuths, counter-clockwise from azimuth_from to azimuth_to. The same azimuth
// twice would read as the whole turn (units/arc.hpp): that must be written as such (to 360 deg
// past from), never fall out of a typing slip.
void read_arc(const TableReader& t, units::Arc& arc) {
  double& from = arc.from;
  double& to = arc.to;
  from = t.quantity("azimuth_from", Kind::Angle, kAnyAzimuth);
  to = t.quantity("azimuth_to", Kind::Angle, kAnyAzimuth);
  if (to == from)
    throw t.error("azimuth_to", "equals azimuth_from: an arc from an azimuth to itself spans nothing; expected another azimuth (for "
                                "the whole turn, azimuth_to 360 deg past azimuth_from)");
  // Counter-clockwise from `from`, an arc spans at most a whole turn: a `to` further round
  // would be read modulo the turn (700 deg past 0 as 340 deg), not as written.
  if (std::abs(to - from) > 2 * units::pi * (1 + 1e-12))
    throw t.error("azimuth_to", fmt::format("is {:g} deg from azimuth_from: an arc spans at most a whole turn (360 deg); expected "
                                            "azimuth_to within 360 deg of azimuth_from",
                                            std::abs(to - from) / units::degree));
}

// A part is placed one way or the other: keys of the other way are refused.
void refuse_with(const TableReader& t, std::initializer_list<const char*> keys, const char* chosen) {
  for (const char* key : keys)
    if (t.has(key)) throw t.error(key, fmt::format("give either `{}` or the arc keys, not both", chosen));
}

void read_guard(const TableReader& t, GuardSpec& g, bool with_geometry, std::vector<std::string>& notes) {
  g.name = t.string_or("name", g.name, {});
  if (with_geometry) {
    if (t.has("along")) {
      refuse_with(t, {"azimuth_from", "azimuth_to"}, "along");
      g.along = t.points("along", Kind::Length, kPlanCoordinate, 2, 64);
      if (t.has("top")) g.top = t.quantity("top", Kind::Length, Range::positive_up_to(2));  // (left out: the deck plate's height)
    } else {
      read_arc(t, g.azimuth);
    }
    g.bottom = t.quantity_or("bottom", Kind::Length, g.bottom, Range::between(0, 1));
  }
  // A guard named as a flap but given no kind is a chain curtain, as every guard without one
  // is (and was before flaps existed): said, since the file reads otherwise.
  if (!t.has("kind")) {
    std::string lower = g.name;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (lower.find("flap") != std::string::npos)
      notes.push_back(t.error("name", "named as a flap but given no `kind`: read as a chain curtain (the default); write "
                                      "kind = \"flap\" for a solid flap, or kind = \"chains\" to say it is a curtain")
                          .what());
  }
  const std::string kind = t.string_or("kind", "chains", {"chains", "flap"});
  g.kind = kind == "flap" ? GuardSpec::Kind::Flap : GuardSpec::Kind::Chains;
  if (g.kind == GuardSpec::Kind::Flap) {
    for (const char* key : {"openness", "pass_speed_factor"})
      if (t.has(key)) throw t.error(key, "a flap is a solid plate: nails do not pass between links (set kind = \"chains\" for a curtain)");
    g.openness = 0.0, g.pass_speed_factor = 1.0;
    g.thickness = t.quantity_or("thickness", Kind::Length, g.thickness, Range::between(0.0005, 0.05));
    g.density = t.quantity_or("density", Kind::Density, g.density, Range::between(100, 10000));
    g.panel_width = t.quantity_or("panel_width", Kind::Length, 0.0, Range::between(0.01, 10));
  } else {
    for (const char* key : {"thickness", "density", "panel_width"})
      if (t.has(key)) throw t.error(key, "only a flap (kind = \"flap\") has this; a chain curtain has openness and pass_speed_factor");
  }
  g.openness = t.quantity_or("openness", Kind::Dimensionless, g.openness, Range::UnitInterval);
  g.pass_speed_factor = t.quantity_or("pass_speed_factor", Kind::Dimensionless, g.pass_speed_factor, Range::UnitInterval);
  g.restitution = t.quantity_or("restitution", Kind::Dimensionless, g.restitution, Range::UnitInterval);
  g.friction = t.quantity_or("friction", Kind::Dimensionless, g.friction, Range::between(0, 2));
}

void read_housing(const TableReader& t, HousingSpec& h, bool several_spindles, std::vector<std::string>& notes) {
  // One spindle: a round deck of deck_radius. Several: the deck's outline follows their tip
  // circles at `margin`, and deck_radius has no meaning.
  h.margin = t.quantity_or("margin", Kind::Length, h.margin, Range::between(0.005, 1));
  if (several_spindles && t.has("deck_radius"))
    throw t.error("deck_radius", "with several spindles the deck's outline follows their tip circles; set housing.margin instead");
  if (!several_spindles && t.has("deck_radius") && t.has("margin"))
    throw t.error("margin", "is unused: deck_radius gives the deck's size (margin sets it only when deck_radius is left out); remove "
                            "one of the two");
  if (auto r = t.optional_quantity("deck_radius", Kind::Length, Range::positive_up_to(10))) h.deck_radius = *r;
  h.skirt_bottom = t.quantity_or("skirt_bottom", Kind::Length, h.skirt_bottom, Range::between(0, 1));
  // The deck plate's height may be given instead of the skirt's depth: then the skirt's
  // bottom moves alone (a sweep of housing.skirt_bottom keeps the plate where it is; with
  // skirt_depth it moves the whole deck).
  if (t.has("deck_top") && t.has("skirt_depth"))
    throw t.error("deck_top", "give either deck_top (the plate's height above ground) or skirt_depth, not both");
  if (auto top = t.optional_quantity("deck_top", Kind::Length, Range::between(0.001, 2))) {
    if (!(*top - h.skirt_bottom >= 0.001))
      throw t.error("deck_top", fmt::format("expected the deck plate at least 1 mm above the skirt's bottom ({} m)", h.skirt_bottom));
    h.skirt_depth = *top - h.skirt_bottom;
  }
  h.skirt_depth = t.quantity_or("skirt_depth", Kind::Length, h.skirt_depth, Range::between(0.001, 1));
  h.friction = t.quantity_or("friction", Kind::Dimensionless, h.friction, Range::between(0, 2));
  if (auto r = t.table("restitution")) h.restitution = read_restitution(*r);
  const auto all_guard_tables = t.array_of_tables("guards");
  std::vector<TableReader> guard_tables;  // of the guards present, in order
  for (const auto& g : all_guard_tables) {
    GuardSpec guard;
    read_guard(g, guard, true, notes);
    // A guard described but not fitted (present = false: a design without it, or an
    // uncertainty study's discrete input): checked as any other, named in the report, not built.
    if (!g.boolean_or("present", true)) {
      g.refuse_unknown_keys();
      h.absent_guards.push_back(guard.name);
      continue;
    }
    guard_tables.push_back(g);
    if (!guard.along.empty()) {
      if (guard.bottom >= h.guard_top(guard))
        throw g.error("bottom", fmt::format("expected the curtain's lower edge below its top ({} m)", h.guard_top(guard)));
    }
    g.refuse_unknown_keys();
    h.guards.push_back(guard);
  }
  for (const auto& o : t.array_of_tables("openings")) {
    OpeningSpec op;
    op.name = o.string_or("name", op.name, {});
    read_arc(o, op.azimuth);
    if (o.has("top")) op.top = o.quantity("top", Kind::Length, Range::between(0, 2));
    // (Within a micrometre: the same height written in two units is no opening.)
    if (h.opening_top(op) <= h.skirt_bottom + 1e-6)
      throw o.error("top", fmt::format("expected the opening's upper edge above the skirt's bottom ({:.4g} m): an opening up to it cuts "
                                       "nothing",
                                       h.skirt_bottom));
    op.chute_length = o.quantity_or("chute_length", Kind::Length, 0.0, Range::between(0, 3));
    if (o.has("chute_end_top")) op.chute_end_top = o.quantity("chute_end_top", Kind::Length, Range::between(0, 2));
    if (o.has("chute_end_top") && op.chute_length == 0.0)
      throw o.error("chute_end_top", "a chute's mouth needs a chute: set chute_length too");
    if (h.chute_end_top(op) <= h.skirt_bottom + 1e-6)
      throw o.error("chute_end_top", fmt::format("expected the chute's mouth above the skirt's bottom ({:.4g} m)", h.skirt_bottom));
    o.refuse_unknown_keys();
    h.openings.push_back(op);
  }
  // Openings round the whole turn leave no skirt: a deck without one is a skirt whose foot is
  // at the plate, not openings. (Covered when every arc's end lies inside some arc: a gap
  // would begin at an arc's end.)
  if (!h.openings.empty()) {
    bool whole_turn = true;
    for (const auto& a : h.openings) {
      bool covered = false;
      for (const auto& b : h.openings) {
        // a's end inside b, a nanoradian clear of b's end (its start included: arcs that meet).
        double off = b.azimuth.offset(a.azimuth.to);
        if (off > units::two_pi - 1e-9) off = 0;
        covered = covered || off < b.azimuth.span() - 1e-9;
      }
      whole_turn = whole_turn && covered;
    }
    if (whole_turn) {
      const auto tables = t.array_of_tables("openings");
      throw tables.back().error(
          "azimuth_to", fmt::format("the opening{} cut{} the skirt round the whole turn, so no skirt is left; expected openings that "
                                    "leave some skirt (a deck without a skirt: housing.skirt_bottom up to the plate)",
                                    h.openings.size() > 1 ? "s together" : "", h.openings.size() > 1 ? "" : "s"));
    }
  }
  // A guard given by azimuths hangs below the skirt and across the openings it spans, up
  // to their tops: its lower edge may stand above the skirt's bottom (a flap hung across an
  // opening to any height) only where it spans an opening whose top is above it.
  for (std::size_t i = 0; i < h.guards.size(); ++i) {
    const GuardSpec& guard = h.guards[i];
    if (!guard.along.empty() || guard.bottom < h.skirt_bottom) continue;
    bool hangs = false;
    for (const auto& op : h.openings)
      hangs = hangs || (guard.azimuth.overlaps(op.azimuth) && guard.bottom < op.top);
    if (!hangs)
      throw guard_tables[i].error(
          "bottom", fmt::format("expected the curtain's lower edge below the skirt bottom ({} m), or below the top of an opening "
                                "its azimuths span (it would hang nowhere)",
                                h.skirt_bottom));
  }
  for (const auto& d : t.array_of_tables("deflectors")) {
    DeflectorSpec def;
    def.name = d.string_or("name", def.name, {});
    if (d.has("along")) {
      refuse_with(d, {"azimuth_from", "azimuth_to", "radius"}, "along");
      def.along = d.points("along", Kind::Length, kPlanCoordinate, 2, 64);
    } else {
      read_arc(d, def.azimuth);
      def.radius = d.quantity("radius", Kind::Length, Range::positive_up_to(10));
    }
    def.bottom = d.quantity("bottom", Kind::Length, Range::between(0, 5));
    def.top = d.quantity("top", Kind::Length, Range::positive_up_to(5));
    if (def.top <= def.bottom) throw d.error("top", "expected the top above the bottom");
    d.refuse_unknown_keys();
    h.deflectors.push_back(def);
  }
  t.refuse_unknown_keys();
}

// A value as the key it will be set on takes it: a string as written, a number as text.
std::string value_text(const TableReader& t, const char* key) {
  if (t.is_string(key)) return t.string_or(key, "", {});
  return fmt::format("{:.17g}", t.quantity(key, Kind::Dimensionless));
}

void read_uncertainty(const TableReader& t, UncertaintySpec& u) {
  u.base_draws = t.integer_or("base_draws", u.base_draws, 2, 4096);
  u.replicates = t.integer_or("replicates", u.replicates, 10, 1000000);
  if (t.has("objects")) u.objects = t.integer_or("objects", 0, 100, 1'000'000'000);
  for (const auto& i : t.array_of_tables("inputs", 16)) {
    UncertainInput in;
    in.parameter = i.string_or("parameter", "", {});
    if (in.parameter.empty()) throw i.error("parameter", "missing; expected a sweep parameter or a dotted key of this file");
    if (i.has("values")) {
      // A discrete input: its values as the key takes them, drawn with equal probability.
      in.values = i.strings("values", 16);
      if (in.values.size() < 2) throw i.error("values", "expected at least two values for the key to take, as strings (\"cw\", \"ccw\")");
      for (const char* k : {"low", "high", "distribution", "mode", "sd"})
        if (i.has(k)) throw i.error(k, "a discrete input (values = [...]) has no range or distribution; give values or low/high, not both");
      in.distribution = "discrete";
      in.basis = i.string_or("basis", "", {});
      if (in.basis.empty()) throw i.error("basis", "missing; say what the choice rests on (a source, or \"estimate: ...\")");
      in.line = i.line_of("parameter");
      i.refuse_unknown_keys();
      u.inputs.push_back(in);
      continue;
    }
    if (!i.has("low")) throw i.error("low", "missing; expected the range's low end as the key takes it (\"0.7\", \"0 deg\"), or values = [...]");
    if (!i.has("high")) throw i.error("high", "missing; expected the range's high end as the key takes it");
    in.low = value_text(i, "low");
    in.high = value_text(i, "high");
    in.distribution = i.string_or("distribution", "uniform", {"uniform", "triangular", "normal", "loguniform"});
    if (i.has("mode")) {
      if (in.distribution != "triangular") throw i.error("mode", "only a triangular distribution has a mode");
      in.mode = value_text(i, "mode");
    }
    if (i.has("sd")) {
      if (in.distribution != "normal") throw i.error("sd", "only a normal distribution has a standard deviation");
      in.sd = value_text(i, "sd");
    }
    in.basis = i.string_or("basis", "", {});
    if (in.basis.empty()) throw i.error("basis", "missing; say what the range rests on (a source, or \"estimate: ...\")");
    in.line = i.line_of("parameter");
    i.refuse_unknown_keys();
    u.inputs.push_back(in);
  }
  t.refuse_unknown_keys();
}

void read_zone(const TableReader& t, OperatorZoneSpec& z) {
  const std::string kind = t.string_or("kind", "derived", {"derived", "sector"});
  if (kind == "sector") {
    z.kind = OperatorZoneSpec::Kind::Sector;
    read_arc(t, z.azimuth);
    z.bottom = t.quantity_or("bottom", Kind::Length, 0.0, Range::between(0, 10));
    z.top = t.quantity("top", Kind::Length, Range::positive_up_to(10));
    if (z.top <= z.bottom) throw t.error("top", "expected the top above the bottom");
  } else {
    z.kind = OperatorZoneSpec::Kind::Derived;
    z.seat_x = t.quantity_or("seat_x", Kind::Length, z.seat_x, Range::between(-20, 20));
    z.seat_y = t.quantity_or("seat_y", Kind::Length, z.seat_y, Range::between(-20, 20));
    z.seat_z = t.quantity_or("seat_z", Kind::Length, z.seat_z, Range::between(0, 5));
    z.shoulder_height = t.quantity_or("shoulder_height", Kind::Length, z.shoulder_height, Range::positive_up_to(2));
    z.shoulder_half_width = t.quantity_or("shoulder_half_width", Kind::Length, z.shoulder_half_width, Range::between(0, 1));
    z.reach = t.quantity_or("reach", Kind::Length, z.reach, Range::positive_up_to(3));
    z.knee_height = t.quantity_or("knee_height", Kind::Length, z.knee_height, Range::positive_up_to(2));
  }
  t.refuse_unknown_keys();
}

void read_criteria(const TableReader& t, CriteriaSpec& c) {
  // Limits are percentages written with their unit: a bare 0.5 could mean 0.5 % or 50 %.
  c.hits_zone = t.percentage_or("hits_zone", c.hits_zone);
  c.punctures_zone = t.percentage_or("punctures_zone", c.punctures_zone);
  c.hits_outside = t.percentage_or("hits_outside", c.hits_outside);
  c.punctures_outside = t.percentage_or("punctures_outside", c.punctures_outside);
  c.counted_height = t.optional_quantity("counted_height", Kind::Length, Range::between(0, 5));
  c.denominator = t.string_or("denominator", "nails_fed", {"nails_fed", "marks"}) == "marks" ? CriteriaSpec::Denominator::Marks
                                                                                             : CriteriaSpec::Denominator::NailsFed;
  // 0 would let any mower pass: a verdict that says nothing.
  c.required_pass_probability =
      t.quantity_or("required_pass_probability", Kind::Dimensionless, c.required_pass_probability, Range{0.0, 1.0, true});
  t.refuse_unknown_keys();
}

void read_run(const TableReader& t, RunSpec& r) {
  r.replicates = t.integer_or("replicates", r.replicates, 1, 100'000'000);
  r.seed = t.unsigned64_or("seed", r.seed);
  r.threads = static_cast<int>(t.integer_or("threads", r.threads, 0, 1024));
  // Narrower than 0.001 needs millions of replicates; 0 would never be met.
  r.target_half_width = t.optional_quantity("target_half_width", Kind::Dimensionless, Range::between(0.001, 0.5));
  r.until_settled = t.boolean_or("until_settled", r.until_settled);
  r.max_replicates = t.integer_or("max_replicates", r.max_replicates, 1, 100'000'000);
  const std::string estimator = t.string_or("estimator", "narrower", {"narrower", "replicates", "every_nail"});
  r.estimator = estimator == "replicates" ? RunSpec::Estimator::Replicates
                : estimator == "every_nail" ? RunSpec::Estimator::EveryNail
                                            : RunSpec::Estimator::Narrower;
  // Below 10 um the chord count (and run time) explodes for no gain in accuracy.
  r.chord_tolerance = t.quantity_or("chord_tolerance", Kind::Length, r.chord_tolerance, Range::between(1e-5, 0.1));
  // A nail thrown at blade speed reaches the board in well under 0.1 s; shorter limits cut
  // the test off before it happens.
  if (t.has("time_limit")) r.time_limit = t.quantity("time_limit", Kind::Time, Range::between(0.1, 60));
  if (t.has("max_bounces")) r.max_bounces = static_cast<int>(t.integer_or("max_bounces", 0, 1, 10000));
  r.max_gentle_contacts = static_cast<int>(t.integer_or("max_gentle_contacts", r.max_gentle_contacts, 1, 10'000'000));
  if (t.has("max_strikes")) r.max_strikes = static_cast<int>(t.integer_or("max_strikes", 0, 1, 100000));
  r.max_contacts_per_pass = static_cast<int>(t.integer_or("max_contacts_per_pass", r.max_contacts_per_pass, 1, 100000));
  r.rest_speed = t.quantity_or("rest_speed", Kind::Speed, r.rest_speed, Range::between(0.01, 5));
  r.reference_contact_search = t.string_or("contact_search", "advancement", {"advancement", "fixed_steps"}) == "fixed_steps";
  r.restitution_law = t.string_or("restitution_law", "energetic", {"energetic", "poisson"}) == "poisson" ? RestitutionLaw::Poisson
                                                                                                        : RestitutionLaw::Energetic;
  t.refuse_unknown_keys();
}

// The cutting edge's shape and the nail-on-blade friction ([blade.edge]).
void read_edge(const TableReader& t, EdgeSpec& e, double thickness) {
  e.bevel_angle = t.quantity_or("bevel_angle", Kind::Angle, e.bevel_angle, Range::between(5 * units::degree, 90 * units::degree));
  e.bevel_side = t.string_or("bevel_side", "top", {"top", "bottom"}) == "bottom" ? EdgeSpec::Side::Bottom : EdgeSpec::Side::Top;
  e.width = t.quantity_or("width", Kind::Length, e.width, Range::between(0.005, 0.5));
  const double run = e.bevel_angle < 0.5 * units::pi ? thickness / std::tan(e.bevel_angle) : 0.0;
  if (run > e.width)
    throw t.error("bevel_angle", fmt::format("a {:.4g} deg bevel on a {:.4g} mm blade runs {:.4g} mm back, beyond the edge's width "
                                             "({:.4g} mm): give a steeper bevel or a wider blade",
                                             e.bevel_angle / units::degree, thickness * 1e3, run * 1e3, e.width * 1e3));
  e.sail_height = t.quantity_or("sail_height", Kind::Length, e.sail_height, Range::between(0, 0.2));
  e.sail_angle = t.quantity_or("sail_angle", Kind::Angle, e.sail_angle, Range::between(10 * units::degree, 90 * units::degree));
  e.friction = t.quantity_or("friction", Kind::Dimensionless, e.friction, Range::between(0, 2));
  t.refuse_unknown_keys();
}

// A blade with its geometry (height, thickness, edge) from a [blade]-like table.
void read_blade_and_geometry(const TableReader& t, SpindleSpec& sp) {
  if (t.has("lift_angle"))
    throw t.error("lift_angle",
                  "no longer a key: the blade's lift now follows from its edge's geometry and the nail-on-blade friction; give "
                  "[blade.edge] bevel_angle, bevel_side, width, sail_height, sail_angle and friction instead (docs/model.md §5.1)");
  sp.blade = read_blade(t);
  sp.geometry.height = t.quantity_or("height", Kind::Length, sp.geometry.height, Range::between(0.005, 1));
  sp.geometry.thickness = t.quantity_or("thickness", Kind::Length, sp.geometry.thickness, Range::between(0.0005, 0.05));
  if (const auto edge = t.table("edge"))
    read_edge(*edge, sp.geometry.edge, sp.geometry.thickness);
  else
    read_edge(TableReader(toml::table{}, t.file(), t.path() + ".edge"), sp.geometry.edge, sp.geometry.thickness);
  t.refuse_unknown_keys();
}

// [blade] (one spindle at the origin), or [[spindles]] with blades inline or by name
// from [blades.NAME] (a deck of identical blades is written once).
void read_spindles(const TableReader& root, std::vector<SpindleSpec>& spindles) {
  spindles.clear();
  const auto blade_table = root.table("blade");
  const auto tables = root.array_of_tables("spindles", 8);
  if (blade_table && !tables.empty())
    throw root.error("spindles", "give either [blade] (one spindle at the origin) or [[spindles]], not both");
  if (blade_table) {
    SpindleSpec sp;
    read_blade_and_geometry(*blade_table, sp);
    spindles.push_back(sp);
    return;
  }
  if (tables.empty()) throw root.error("blade", "missing; expected a [blade] table, or [[spindles]] for a deck of several");
  const auto named = root.table("blades");
  std::set<std::string> used;
  for (const auto& t : tables) {
    SpindleSpec sp;
    if (t.is_string("blade")) {
      sp.blade_name = t.string_or("blade", "", {});
      const auto b = named ? named->table(sp.blade_name) : std::nullopt;
      if (!b) throw t.error("blade", fmt::format("no [blades.{}] table gives this blade", sp.blade_name));
      read_blade_and_geometry(*b, sp);
      used.insert(sp.blade_name);
    } else if (const auto b = t.table("blade")) {
      read_blade_and_geometry(*b, sp);
    } else {
      throw t.error("blade", "missing; expected the name of a [blades.NAME] table or an inline [spindles.blade] table");
    }
    sp.x = t.quantity_or("x", Kind::Length, 0.0, Range::between(-10, 10));
    sp.y = t.quantity_or("y", Kind::Length, 0.0, Range::between(-10, 10));
    sp.geometry.height = t.quantity_or("height", Kind::Length, sp.geometry.height, Range::between(0.005, 1));
    sp.sense = t.string_or("sense", "ccw", {"ccw", "cw"}) == "cw" ? -1 : +1;
    if (t.is_string("phase") && t.string_or("phase", "", {}) == "random")
      sp.phase.reset();
    else
      sp.phase = t.optional_quantity("phase", Kind::Angle, kAnyAzimuth);
    t.refuse_unknown_keys();
    spindles.push_back(sp);
  }
  if (named) {
    for (const auto& name : named->keys())
      if (!used.count(name)) throw named->error(name, "no spindle uses this blade; remove it or give it to a [[spindles]] entry");
    named->refuse_unknown_keys();
  }
  // Blades must not overlap: two tip circles closer than their radii would cut each other.
  for (std::size_t i = 0; i < spindles.size(); ++i)
    for (std::size_t j = i + 1; j < spindles.size(); ++j) {
      const double d = std::hypot(spindles[i].x - spindles[j].x, spindles[i].y - spindles[j].y);
      if (d < spindles[i].blade.tip_radius() + spindles[j].blade.tip_radius() &&
          std::abs(spindles[i].geometry.height - spindles[j].geometry.height) <
              0.5 * (spindles[i].geometry.thickness + spindles[j].geometry.thickness))
        throw tables[j].error("x", fmt::format("spindle {}'s tip circle overlaps spindle {}'s in the same plane ({:.3f} m apart, "
                                               "radii {:.3f} and {:.3f} m): stagger their heights or move them apart",
                                               j + 1, i + 1, d, spindles[i].blade.tip_radius(), spindles[j].blade.tip_radius()));
    }
}

// Keys of the generated set-up that a mesh replaces are refused, never silently ignored.
void refuse_what_meshes_replace(const TableReader& root, const std::vector<MeshFile>& meshes) {
  auto first = [&](auto is) -> const MeshFile* {
    for (const auto& m : meshes)
      if (is(m.label)) return &m;
    return nullptr;
  };
  if (const MeshFile* deck = first([](MeshLabel l) { return l == MeshLabel::Housing; }))
    if (auto h = root.table("housing")) {
      const std::string replaces = fmt::format("the housing mesh {} replaces the generated deck and skirt", deck->path);
      for (const char* key : {"deck_radius", "skirt_bottom", "skirt_depth", "deck_top", "margin", "openings"})
        if (h->has(key)) throw h->error(key, replaces + "; remove this key (housing.restitution and housing.friction still apply)");
      // Guards along the generated outline have no outline to follow; along a polyline
      // (with its own top) they hang anywhere. Deflectors stand on their own.
      for (const auto& g : h->array_of_tables("guards")) {
        if (!g.has("along"))
          throw g.error("azimuth_from", replaces +
                                            ", so a guard cannot follow its outline: give the curtain's "
                                            "path as `along = [[x, y], ...]` with `top`, or as a mesh with label = \"guard\"");
        if (!g.has("top")) throw g.error("along", replaces + ": give the curtain's upper edge as `top`");
      }
    }
  if (const MeshFile* board = first(is_board))
    if (auto t = root.table("target"))
      for (const char* key : {"distance", "bottom", "top", "segments", "shape"})
        if (t->has(key))
          throw t->error(key, fmt::format("the target mesh {} replaces the generated board ring; remove this key", board->path));
}

// The scenario's parts, each from its table (keys checked, unknown ones refused).
void read_ground(const TableReader& g, GroundSpec& ground, bool field) {
  // The kind first: its figures are the defaults the keys below override.
  std::vector<std::string> kinds;
  for (const auto& k : kGroundKinds) kinds.emplace_back(k.name);
  ground.kind = g.string_or("kind", "turf", kinds);
  if (const GroundKind* k = ground_kind(ground.kind)) {
    ground.restitution = k->restitution, ground.friction = k->friction, ground.roughness = k->roughness_deg * units::degree;
    ground.angle_exponent = k->angle_exponent;
    ground.rolling_resistance = k->rolling_resistance, ground.penetrability = k->penetrability;
    ground.max_restitution = std::max(ground.max_restitution, ground.restitution);
  }
  ground.restitution = g.quantity_or("restitution", Kind::Dimensionless, ground.restitution, Range::UnitInterval);
  ground.angle_exponent = g.quantity_or("angle_exponent", Kind::Dimensionless, ground.angle_exponent, Range::between(0, 3));
  ground.max_restitution = g.quantity_or("max_restitution", Kind::Dimensionless, ground.max_restitution, Range::between(0, 0.99));
  if (ground.max_restitution < ground.restitution)
    throw g.error("max_restitution", fmt::format("expected at least the perpendicular restitution ({:g})", ground.restitution));
  ground.friction = g.quantity_or("friction", Kind::Dimensionless, ground.friction, Range::between(0, 2));
  ground.roughness = g.quantity_or("roughness", Kind::Angle, ground.roughness, Range::between(0, 45 * units::degree));
  if (!field && g.has("rolling_resistance"))
    throw g.error("rolling_resistance", "a field scenario's ([field]): round objects roll there; the J232 test's nails do not");
  ground.rolling_resistance = g.quantity_or("rolling_resistance", Kind::Dimensionless, ground.rolling_resistance, Range::between(0, 2));
  ground.penetrability = g.quantity_or("penetrability", Kind::Dimensionless, ground.penetrability, Range::between(0, 100));
  g.refuse_unknown_keys();
}

// Into s.target; the blades and the deck already read (the board must stand outside the deck,
// its top, written or derived, above its bottom).
void read_target(const TableReader& t, Scenario& s) {
  TargetSpec& target = s.target;
  target.distance = t.quantity_or("distance", Kind::Length, target.distance, Range::between(0.05, 10));
  target.bottom = t.quantity_or("bottom", Kind::Length, target.bottom, Range::between(0, 5));
  if (t.has("top")) target.top = t.quantity("top", Kind::Length, Range::positive_up_to(10));
  target.segments = static_cast<int>(t.integer_or("segments", target.segments, 16, 3600));
  const std::string shape = t.string_or("shape", "circle", {"circle", "outline"});
  target.shape = shape == "outline" ? TargetSpec::Shape::Outline : TargetSpec::Shape::Circle;
  if (s.target_top() <= target.bottom) throw t.error("top", "expected the board's top above its bottom");
  if (s.reach() + target.distance <= s.deck_radius()) throw t.error("distance", "expected the board outside the mower deck");
  t.refuse_unknown_keys();
}

// A mesh file's path is relative to the scenario's folder (`base`).
MeshFile read_mesh_file(const TableReader& m, const std::filesystem::path& base, std::vector<std::string>& notes) {
  MeshFile mesh;
  const std::string path = m.string_or("path", "", {});
  if (path.empty()) throw m.error("path", "missing; expected the mesh file's path (OBJ, OFF, PLY or STL)");
  mesh.path = (base / path).string();
  mesh.line = m.line_of("path");
  const std::string label = m.string_or("label", "", {kMeshLabelNames.begin(), kMeshLabelNames.end()});
  if (label.empty()) throw m.error("label", "missing; expected one of ground, housing, deflector, guard, target, operator_zone");
  mesh.label = static_cast<MeshLabel>(std::find(kMeshLabelNames.begin(), kMeshLabelNames.end(), label) - kMeshLabelNames.begin());
  mesh.scale = m.quantity_or("scale", Kind::Dimensionless, 1.0, Range::between(1e-6, 1e3));
  if (mesh.label == MeshLabel::Guard) read_guard(m, mesh.guard, false, notes);
  m.refuse_unknown_keys();
  return mesh;
}

void read_board(const TableReader& b, BoardSpec& board) {
  board.puncture_energy_per_width =
      b.quantity_or("puncture_energy_per_width", Kind::EnergyPerLength, board.puncture_energy_per_width, Range::between(1, 1e4));
  board.hit_fraction = b.quantity_or("hit_fraction", Kind::Dimensionless, board.hit_fraction, Range::UnitInterval);
  board.crush_depth = b.quantity_or("crush_depth", Kind::Length, board.crush_depth, Range::between(1e-4, 0.1));
  b.refuse_unknown_keys();
}

void read_air(const TableReader& a, AirSpec& air) {
  air.drag = a.boolean_or("drag", air.drag);
  // Air at any altitude or temperature a mower meets is 0.9-1.4 kg/m^3; water is 1000.
  air.density = a.quantity_or("density", Kind::Density, air.density, Range::between(0, 5));
  air.cd_normal = a.quantity_or("cd_normal", Kind::Dimensionless, air.cd_normal, Range::between(0, 3));
  air.cd_axial = a.quantity_or("cd_axial", Kind::Dimensionless, air.cd_axial, Range::between(0, 3));
  air.spin_average = a.boolean_or("spin_average", air.spin_average);
  a.refuse_unknown_keys();
}


// The field a hazard scenario mows (FieldSpec). `s` has its blades and deck read.
// `s_notes`: where what it accepted but says goes (Scenario::notes).
void read_field(const TableReader& t, const Scenario& s, bool root_has_restitution, FieldSpec& f, std::vector<std::string>& s_notes) {
  f.present = true;
  f.ground_speed = t.quantity_or("ground_speed", Kind::Speed, f.ground_speed, Range::positive_up_to(15));
  f.range = t.quantity_or("range", Kind::Length, f.range, Range::between(5, 500));
  f.cell = t.quantity_or("cell", Kind::Length, f.cell, Range::between(0.1, 10));
  if (f.range / f.cell > 1000) throw t.error("cell", fmt::format("expected at most 1000 cells across the range ({:g} m): a coarser cell", f.range));
  if (f.cell > 0.5 * f.range)
    throw t.error("cell", fmt::format("expected a cell at most half the range ({:g} m): the maps need cells across it", f.range));
  f.objects_simulated = t.integer_or("objects_simulated", f.objects_simulated, 1, 1'000'000'000);
  f.person_energy = t.quantity_or("person_energy", Kind::Energy, f.person_energy, Range::between(0.01, 1e5));
  f.presented_area = t.quantity_or("presented_area", Kind::Area, f.presented_area, Range::between(0.01, 10));
  f.acceptable_area = t.quantity_or("acceptable_area", Kind::Area, f.acceptable_area, Range::between(0.1, 1e6));
  f.person_height = t.quantity_or("person_height", Kind::Length, f.person_height, Range::between(0.3, 2.5));
  f.passes_per_season = t.integer_or("passes_per_season", f.passes_per_season, 1, 100000);
  f.people_per_pass = t.quantity_or("people_per_pass", Kind::Dimensionless, f.people_per_pass, Range::between(0, 1e6));
  f.vehicle_energy = t.quantity_or("vehicle_energy", Kind::Energy, f.vehicle_energy, Range::between(0.001, 1e5));
  f.windshield_bottom = t.quantity_or("windshield_bottom", Kind::Length, f.windshield_bottom, Range::between(0, 5));
  f.windshield_top = t.quantity_or("windshield_top", Kind::Length, f.windshield_top, Range::between(0, 5));
  if (f.windshield_top <= f.windshield_bottom) throw t.error("windshield_top", "expected the windshield's top above its bottom");

  // Where a blade can reach an object: its lower face; where the deck stops one: the gap
  // objects enter through (a front opening's chains, if any, drag over them). A mesh deck's
  // is not known, and not checked.
  const double lowest_face = s.lowest_blade_face();
  const std::optional<double> front_gap = s.front_gap();
  f.updraft_speed = t.quantity_or("updraft_speed", Kind::Speed, f.updraft_speed, Range::between(0, 100));
  f.support_height = t.quantity_or("support_height", Kind::Length, f.support_height, Range::between(0, 0.2));
  const std::string shape = t.string_or("support_shape", "exponential", {"exponential", "half_normal"});
  if (f.support_height == 0 && t.has("support_shape"))
    throw t.error("support_shape", "a support_height above 0: with none, every object lies on the plane and there is no shape to give");
  f.support_shape = shape == "half_normal" ? FieldSpec::SupportShape::HalfNormal : FieldSpec::SupportShape::Exponential;
  const auto tables = t.array_of_tables("objects", 16);
  if (tables.empty())
    throw t.error("objects", "missing: a field without objects throws nothing; expected [[field.objects]] tables with kind, "
                             "median_size and per_area");
  for (const auto& o : tables) {
    FieldObjectSpec obj;
    const std::string kind = o.string_or("kind", "stone", {"stone", "steel_ball"});
    obj.kind = kind == "steel_ball" ? FieldObjectSpec::Kind::SteelBall : FieldObjectSpec::Kind::Stone;
    obj.name = o.string_or("name", kind == "steel_ball" ? "steel balls" : "stones", {});
    if (obj.kind == FieldObjectSpec::Kind::SteelBall) {
      // A ball bearing: one size, steel, smooth, the blade's own restitution on steel.
      obj.density = 7850, obj.spread = 1.0, obj.drag_coefficient = 0.47, obj.embedment = 0.0;
      obj.restitution.reset();
      obj.rolls = true;
    }
    // No default size: how far objects fly and how many the blade reaches follow from it.
    if (!o.has("median_size")) throw o.error("median_size", "missing: the objects' median size, such as \"15 mm\"");
    obj.median_size = o.quantity("median_size", Kind::Length, Range::between(0.001, 0.3));
    obj.spread = o.quantity_or("spread", Kind::Dimensionless, obj.spread, Range::between(1, 5));
    const bool one_size = obj.spread == 1.0;
    obj.min_size = o.quantity_or("min_size", Kind::Length, one_size ? obj.median_size : std::min(obj.min_size, obj.median_size),
                                 Range::between(0.001, 0.3));
    obj.max_size = o.quantity_or("max_size", Kind::Length, one_size ? obj.median_size : std::max(obj.max_size, obj.median_size),
                                 Range::between(0.001, 0.3));
    if (obj.min_size == obj.max_size) obj.spread = 1.0;  // one size: nothing to spread
    if (!(obj.min_size <= obj.median_size && obj.median_size <= obj.max_size)) {
      // Blamed on the bound the file gave out of order (the median when the file gave neither).
      const char* key = obj.min_size > obj.median_size ? (o.has("min_size") ? "min_size" : "median_size")
                                                       : (o.has("max_size") ? "max_size" : "median_size");
      throw o.error(key, fmt::format("expected min_size ({:g} m) <= median_size ({:g} m) <= max_size ({:g} m)", obj.min_size,
                                     obj.median_size, obj.max_size));
    }
    obj.density = o.quantity_or("density", Kind::Density, obj.density, Range::between(500, 20000));
    if (!o.has("per_area")) throw o.error("per_area", "missing: how many of these objects lie on a square metre, such as \"0.5 m^-2\"");
    obj.per_area = o.quantity("per_area", Kind::PerArea, Range::positive_up_to(10000));
    obj.embedment = o.quantity_or("embedment", Kind::Dimensionless, obj.embedment, Range::between(0, 0.9));
    if (auto e = o.optional_quantity("restitution", Kind::Dimensionless, Range::UnitInterval)) obj.restitution = *e;
    obj.friction = o.quantity_or("friction", Kind::Dimensionless, obj.friction, Range::between(0, 2));
    obj.drag_coefficient = o.quantity_or("drag_coefficient", Kind::Dimensionless, obj.drag_coefficient, Range::between(0, 3));
    obj.rolls = o.boolean_or("rolls", obj.rolls);
    o.refuse_unknown_keys();
    const double top = obj.max_size * (1 - obj.embedment);
    // With supports the model leaves out what stands at or above the gap (pushed aside), and
    // says so.
    if (f.support_height > 0 && front_gap && top >= *front_gap)
      s_notes.push_back(o.error("max_size", fmt::format("the largest stand {:.3g} m above the turf, at or above the deck's front gap "
                                                        "({:.3g} m): those are pushed aside by the deck, not struck",
                                                        top, *front_gap))
                            .what());
    if (f.support_height == 0 && front_gap && top >= *front_gap)
      throw o.error("max_size", fmt::format("objects standing {:.3g} m above the turf cannot pass under the deck's front ({:.3g} m above "
                                            "the turf): the deck pushes them along; expected a smaller max_size or a higher skirt",
                                            top, *front_gap));
    // Lifted by the updraft (its drag above its weight), an object meets the blade in the
    // blade's plane: 3 rho C_d u^2 / (4 rho_s g) is the largest size it lifts.
    const double lifted_up_to = s.lifted_up_to(obj, obj.drag_coefficient, f.updraft_speed);
    // Held up by what they rest on (field.support_height), some of every size reach a blade.
    if (f.support_height == 0 && top <= lowest_face && obj.min_size >= lifted_up_to)
      throw o.error("max_size", fmt::format("no object stands up to the blade: the largest stands {:.3g} m above the turf, the blade's "
                                            "lower face {:.3g} m, and field.support_height is 0 (every object lies on the plane the "
                                            "wheels ride on); the mower passes over them all (expected larger objects, less "
                                            "embedment, a lower cut, field.support_height for what holds them up, or "
                                            "field.updraft_speed to lift them)",
                                            top, lowest_face));
    f.objects.push_back(obj);
  }
  bool blade_restitution_used = false;
  for (const auto& o : f.objects) blade_restitution_used |= !o.restitution;
  if (root_has_restitution && !blade_restitution_used)
    throw t.error("objects", "every object has its own restitution on the blade, so the scenario's [restitution] (the nail's, or a "
                             "steel ball's) is unused: remove it, or leave an object's restitution to it");
  const double deck = s.deck_radius();
  for (const auto& p : t.array_of_tables("planes", 16)) {
    FieldPlaneSpec plane;
    const std::string side = p.string_or("side", "", {"left", "right", "front", "rear"});
    if (side.empty()) throw p.error("side", "missing; expected left, right, front or rear");
    plane.side = side == "left" ? FieldPlaneSpec::Side::Left : side == "right" ? FieldPlaneSpec::Side::Right
                 : side == "front" ? FieldPlaneSpec::Side::Front : FieldPlaneSpec::Side::Rear;
    plane.name = p.string_or("name", side, {});
    plane.distance = p.quantity("distance", Kind::Length, Range::positive_up_to(500));
    if (plane.distance <= deck)
      throw p.error("distance", fmt::format("the plane stands inside the mower's deck ({:.3g} m from its centre); expected a distance "
                                            "beyond it",
                                            deck));
    if (plane.distance >= f.range)
      throw p.error("distance", fmt::format("expected a plane within field.range ({:g} m)", f.range));
    plane.receptor = p.string_or("receptor", "person", {"person", "vehicle"}) == "vehicle" ? FieldPlaneSpec::Receptor::Vehicle
                                                                                          : FieldPlaneSpec::Receptor::Person;
    p.refuse_unknown_keys();
    f.planes.push_back(plane);
  }
  t.refuse_unknown_keys();
}

// A hazard scenario has no test rig: the J232 tables would be silently unused, so they are refused.
void refuse_test_rig(const TableReader& root, const std::vector<MeshFile>& meshes) {
  for (const char* table : {"nail", "feed", "target", "operator_zone", "board", "criteria"})
    if (root.has(table))
      throw root.error(table, fmt::format("a field scenario ([field]) has no J232 test rig, so [{}] has no meaning in it; remove it "
                                          "(j232 run assesses a scenario without [field])",
                                          table));
  for (std::size_t i = 0; i < meshes.size(); ++i)
    if (is_board(meshes[i].label))
      throw root.error("meshes", fmt::format("meshes[{}] is a board ({}); a field scenario has no board", i + 1, mesh_label_name(meshes[i].label)));
  if (auto r = root.table("run"))
    for (const char* key : {"replicates", "estimator", "until_settled", "target_half_width", "max_replicates"})
      if (r->has(key))
        throw r->error(key, "a field scenario simulates field.objects_simulated objects, not replicates of the J232 test; remove it");
}
}  // namespace

namespace {
// The table that gives spindle k's blade (for an error about its height or sail).
TableReader blade_table_of(const TableReader& root, std::size_t k) {
  if (auto b = root.table("blade")) return *b;
  const auto tables = root.array_of_tables("spindles", 8);
  const TableReader& t = tables.at(k);
  if (t.is_string("blade")) return *root.table("blades")->table(t.string_or("blade", "", {}));
  return *t.table("blade");
}

// What each value allows alone is checked where it is read; here, what values must be
// together for a mower that can exist (a blade under its deck plate and above the turf,
// openings and guards below the plate, a board that can carry a counted mark).
// Plan distance from (x, y) to an arc of radius r about the origin: to the circle where the
// point's azimuth lies in the arc, else to its ends.
double distance_to_arc(double x, double y, double r, const units::Arc& arc) {
  const double d = std::hypot(x, y);
  if (d > 0 && arc.contains(std::atan2(y, x))) return std::abs(d - r);
  const auto end = [&](double a) { return std::hypot(x - r * std::cos(a), y - r * std::sin(a)); };
  return std::min(end(arc.from), end(arc.to));
}

// Plan distance from (x, y) to a polyline.
double distance_to_path(double x, double y, const PlanPath& path) {
  double best = HUGE_VAL;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const double ax = path[i][0], ay = path[i][1], dx = path[i + 1][0] - ax, dy = path[i + 1][1] - ay;
    const double len2 = dx * dx + dy * dy;
    const double t = len2 > 0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(x - (ax + t * dx), y - (ay + t * dy)));
  }
  return best;
}

// Whether (x, y) lies inside the deck's plan or on its skirt: a round deck's circle, or within
// the margin of some spindle's tip circle (the outline of several follows their tip circles;
// between two circles the hull reaches a little further, so this may say "outside" there).
bool inside_deck(const Scenario& s, double x, double y) {
  if (s.spindles.size() == 1) return std::hypot(x, y) <= s.deck_radius() + 1e-6;
  for (const auto& sp : s.spindles)
    if (std::hypot(x - sp.x, y - sp.y) <= sp.blade.tip_radius() + s.housing.margin + 1e-6) return true;
  return false;
}

// Points along a deflector's plan path (its arc, or its polyline), about a centimetre apart.
template <class Visit>
void deflector_points(const DeflectorSpec& d, Visit&& visit) {
  if (d.along.empty()) {
    const double span = d.azimuth.span();
    const int n = std::max(2, static_cast<int>(std::ceil(span * d.radius / 0.01)) + 1);
    for (int k = 0; k < n; ++k) {
      const double a = d.azimuth.from + span * k / (n - 1);
      visit(d.radius * std::cos(a), d.radius * std::sin(a));
    }
    return;
  }
  for (std::size_t i = 0; i + 1 < d.along.size(); ++i) {
    const double ax = d.along[i][0], ay = d.along[i][1], bx = d.along[i + 1][0], by = d.along[i + 1][1];
    const int n = std::max(2, static_cast<int>(std::ceil(std::hypot(bx - ax, by - ay) / 0.01)) + 1);
    for (int k = 0; k < n; ++k) visit(ax + (bx - ax) * k / (n - 1), ay + (by - ay) * k / (n - 1));
  }
}

template <class Inside>
bool deflector_enters(const DeflectorSpec& d, Inside&& inside) {
  bool any = false;
  deflector_points(d, [&](double x, double y) { any = any || inside(x, y); });
  return any;
}

// How far (x, y) lies outside the board's wall (< 0: inside it): a ring about the deck's
// centre, or the wall `distance` outside the hull of every tip circle (the hull's distance
// from a point outside it is the greatest over directions u of p.u less its support
// max_k(c_k.u + r_k), sampled every half degree).
double beyond_board(const Scenario& s, double x, double y) {
  if (s.target.shape == TargetSpec::Shape::Circle) return std::hypot(x, y) - (s.reach() + s.target.distance);
  double best = -HUGE_VAL;
  for (int k = 0; k < 720; ++k) {
    const double a = units::two_pi * k / 720, ux = std::cos(a), uy = std::sin(a);
    double support = -HUGE_VAL;
    for (const auto& sp : s.spindles) support = std::max(support, sp.x * ux + sp.y * uy + sp.blade.tip_radius());
    best = std::max(best, x * ux + y * uy - support);
  }
  return best - s.target.distance;
}

// Whether a deflector's plan path meets the board's wall: points on both sides of it, or one
// within a millimetre of it.
bool deflector_crosses_board(const Scenario& s, const DeflectorSpec& d) {
  bool in = false, out = false, on = false;
  deflector_points(d, [&](double x, double y) {
    const double b = beyond_board(s, x, y);
    in = in || b < 0, out = out || b > 0, on = on || std::abs(b) < 1e-3;
  });
  return on || (in && out);
}

// Each blade against the ground, the deck plate and its own arms; a blade hanging below the
// skirt's foot is noted.
void check_blades(const TableReader& root, Scenario& s) {
  const bool generated_deck = s.meshes.empty();
  const double plate = s.housing.plate_height();
  for (std::size_t k = 0; k < s.spindles.size(); ++k) {
    const SpindleSpec& sp = s.spindles[k];
    const double bottom = sp.geometry.height - 0.5 * sp.geometry.thickness;
    const double top = sp.geometry.height + 0.5 * sp.geometry.thickness + sp.geometry.edge.sail_height;
    const TableReader blade = blade_table_of(root, k);
    const auto spindle_height = [&]() -> std::optional<TableReader> {
      if (root.table("blade")) return std::nullopt;
      const auto tables = root.array_of_tables("spindles", 8);
      return tables.at(k).has("height") ? std::optional<TableReader>(tables.at(k)) : std::nullopt;
    }();
    const auto height_error = [&](std::string expected) {
      if (spindle_height) return spindle_height->error("height", std::move(expected));
      return blade.error("height", std::move(expected));
    };
    if (!(bottom > 0))
      throw height_error(fmt::format("the blade's lower face at {:.4g} m is at or below the turf; expected the whole blade above the "
                                     "ground (its mid-plane height less half its thickness above 0)",
                                     bottom));
    if (generated_deck && !(top < plate)) {
      const std::string what = fmt::format(
          "the blade's top{} at {:.4g} m reaches the deck plate at {:.4g} m (housing.skirt_bottom + skirt_depth); expected the whole "
          "blade below the plate",
          sp.geometry.edge.sail_height > 0 ? fmt::format(" (its sail rising {:.4g} m above the blade)", sp.geometry.edge.sail_height) : "",
          top, plate);
      const auto edge = blade.table("edge");
      if (sp.geometry.edge.sail_height > 0 && edge && edge->has("sail_height")) throw edge->error("sail_height", what);
      throw height_error(what);
    }
    // Two knives hung closer than a knife is wide would stand in one another.
    const auto& arms = sp.blade.arms;
    for (std::size_t i = 0; i < arms.size(); ++i)
      for (std::size_t j = 0; j < i; ++j) {
        const double apart = std::hypot(arms[i].pivot_radius * std::cos(arms[i].azimuth) - arms[j].pivot_radius * std::cos(arms[j].azimuth),
                                        arms[i].pivot_radius * std::sin(arms[i].azimuth) - arms[j].pivot_radius * std::sin(arms[j].azimuth));
        if (apart >= sp.geometry.edge.width) continue;
        const auto arm_tables = blade.array_of_tables("arms", 16);
        const std::string what = fmt::format("puts arm {}'s pivot {:.3g} m from arm {}'s, closer than a knife is wide ({:.3g} m, "
                                             "blade.edge.width): the two knives would stand in one another; expected pivots farther "
                                             "apart",
                                             i + 1, apart, j + 1, sp.geometry.edge.width);
        if (i < arm_tables.size()) throw arm_tables[i].error(arm_tables[i].has("azimuth") ? "azimuth" : "pivot_radius", what);
        throw blade.error("arms", what);
      }
    // A blade whose lower face hangs below the skirt's foot: a nail its bevel sends down can
    // leave under the skirt without touching it. A design can mean it (a raised skirt), so it
    // is said, not refused.
    if (generated_deck && bottom < s.housing.skirt_bottom - 1e-12)
      s.notes.push_back(height_error(fmt::format("the blade's lower face at {:.4g} m hangs below the skirt's foot at {:.4g} m "
                                                 "(housing.skirt_bottom): {} it sends down can leave under the skirt without "
                                                 "touching it; a raised skirt may mean this",
                                                 bottom, s.housing.skirt_bottom, root.has("field") ? "objects" : "nails"))
                            .what());
  }
}

// Nothing fixed may stand in a blade's swept disc (its tip circle, over the height from its
// lower face to its top or sail): a panel, a curtain hung along a polyline, another
// spindle's shaft (from its blade up to the deck plate).
void check_swept_discs(const TableReader& root, const Scenario& s) {
  const double plate = s.housing.plate_height();
  const auto housing = root.table("housing");
  const auto band_of = [&](const SpindleSpec& sp) {
    return std::array<double, 2>{sp.geometry.height - 0.5 * sp.geometry.thickness,
                                 sp.geometry.height + 0.5 * sp.geometry.thickness + sp.geometry.edge.sail_height};
  };
  const auto crosses_band = [&](const SpindleSpec& sp, double bottom, double top) {
    const auto band = band_of(sp);
    return bottom < band[1] && top > band[0];
  };
  const auto spindle_name = [&](std::size_t k) {
    return s.spindles.size() > 1 ? fmt::format("spindle {}'s blade", k + 1) : std::string("the blade");
  };
  if (housing) {
    const auto deflectors = housing->array_of_tables("deflectors");
    for (std::size_t i = 0; i < s.housing.deflectors.size() && i < deflectors.size(); ++i) {
      const DeflectorSpec& d = s.housing.deflectors[i];
      for (std::size_t k = 0; k < s.spindles.size(); ++k) {
        const SpindleSpec& sp = s.spindles[k];
        const double off = d.along.empty() ? distance_to_arc(sp.x, sp.y, d.radius, d.azimuth) : distance_to_path(sp.x, sp.y, d.along);
        if (off < sp.blade.tip_radius() && crosses_band(sp, d.bottom, d.top))
          throw deflectors[i].error(d.along.empty() ? "radius" : "along",
                                    fmt::format("puts the panel through {}'s swept disc ({:.3g} m from its axis, within its {:.3g} m tip "
                                                "circle, at the blade's height): expected a panel clear of every blade",
                                                spindle_name(k), off, sp.blade.tip_radius()));
      }
    }
    std::size_t present = 0;
    for (const auto& g : housing->array_of_tables("guards")) {
      if (!g.boolean_or("present", true)) continue;
      const GuardSpec& guard = s.housing.guards.at(present++);
      if (guard.along.empty()) continue;
      const double top = s.housing.guard_top(guard);
      for (std::size_t k = 0; k < s.spindles.size(); ++k) {
        const SpindleSpec& sp = s.spindles[k];
        const double off = distance_to_path(sp.x, sp.y, guard.along);
        if (off < sp.blade.tip_radius() && crosses_band(sp, guard.bottom, top))
          throw g.error("along", fmt::format("hangs the curtain through {}'s swept disc ({:.3g} m from its axis, within its {:.3g} m tip "
                                             "circle, at the blade's height): expected a curtain clear of every blade",
                                             spindle_name(k), off, sp.blade.tip_radius()));
      }
    }
  }
  for (std::size_t i = 0; i < s.spindles.size(); ++i)
    for (std::size_t j = 0; j < s.spindles.size(); ++j) {
      if (i == j) continue;
      const SpindleSpec &a = s.spindles[i], &b = s.spindles[j];
      const double apart = std::hypot(a.x - b.x, a.y - b.y);
      // Spindle i's shaft rises from its blade's top to the plate; blade j sweeps it when it
      // reaches over it at a height on the shaft.
      if (apart < b.blade.tip_radius() && crosses_band(b, band_of(a)[1], plate)) {
        const auto tables = root.array_of_tables("spindles", 8);
        const std::string what = fmt::format("puts spindle {}'s shaft ({:.3g} m from spindle {}'s axis) inside spindle {}'s blade's tip "
                                             "circle ({:.3g} m), which sweeps over it between its own blade and the deck plate: "
                                             "expected the shaft clear of every other blade",
                                             i + 1, apart, j + 1, j + 1, b.blade.tip_radius());
        if (i < tables.size()) throw tables[i].error(tables[i].has("x") ? "x" : "y", what);
        throw root.error("spindles", what);
      }
    }
}

// A generated deck's openings, chutes, panels and curtains end at or below its plate.
void check_deck_plate(const TableReader& root, const Scenario& s) {
  const double plate = s.housing.plate_height();
  const auto housing = root.table("housing");
  if (!s.meshes.empty() || !housing) return;
  const auto openings = housing->array_of_tables("openings");
  for (std::size_t i = 0; i < s.housing.openings.size() && i < openings.size(); ++i) {
    if (s.housing.opening_top(s.housing.openings[i]) > plate + 1e-12)
      throw openings[i].error("top", fmt::format("expected the opening's top at or below the deck plate ({:.4g} m): the skirt it "
                                                 "cuts ends there (an opening to the top of the skirt: leave top out)",
                                                 plate));
    // A discharge chute leads the opening out and down; one rising above the plate would
    // stand where the deck's top is.
    if (s.housing.openings[i].chute_length > 0 && s.housing.chute_end_top(s.housing.openings[i]) > plate + 1e-12)
      throw openings[i].error("chute_end_top", fmt::format("puts the chute's mouth above the deck plate ({:.4g} m); expected a chute "
                                                           "that runs out from its opening at or below the plate",
                                                           plate));
  }
  // A panel standing inside the deck ends at the plate; one rising above it would pass
  // through the plate.
  const auto deflectors = housing->array_of_tables("deflectors");
  for (std::size_t i = 0; i < s.housing.deflectors.size() && i < deflectors.size(); ++i) {
    const DeflectorSpec& d = s.housing.deflectors[i];
    if (d.top > plate + 1e-12 && deflector_enters(d, [&](double x, double y) { return inside_deck(s, x, y); }))
      throw deflectors[i].error("top", fmt::format("raises the panel to {:.4g} m, through the deck plate ({:.4g} m) above the part of "
                                                   "it inside the deck (or on its skirt); expected a top at or below the plate (or the panel outside "
                                                   "the deck)",
                                                   d.top, plate));
  }
  std::size_t present = 0;
  for (const auto& g : housing->array_of_tables("guards")) {
    if (!g.boolean_or("present", true)) continue;
    const GuardSpec& guard = s.housing.guards.at(present++);
    if (!guard.along.empty() && s.housing.guard_top(guard) > plate + 1e-12)
      throw g.error("top", fmt::format("expected the curtain's top at or below the deck plate ({:.4g} m) it hangs from", plate));
  }
}

// The J232 test's board and operator zone around a generated deck (not a field's): the
// board beyond the deck, clear of panels, reaching down to the counted height; a zone on it.
void check_board(const TableReader& root, const Scenario& s) {
  if (s.field.present || !s.meshes.empty()) return;
  const auto housing = root.table("housing");
  const auto target = root.table("target");
  // The board stands around the mower: beyond the deck's edge, not under it.
  {
    const bool several = s.spindles.size() > 1;
    const double board = several ? s.target.distance : s.reach() + s.target.distance;
    const double deck = several ? s.housing.margin : s.deck_radius();
    if (!(board > deck)) {
      const std::string what =
          several ? fmt::format("puts the board {:.3g} m outside the tip circles, within the deck's {:.3g} m margin (housing.margin): the "
                                "board would stand inside the deck; expected a board beyond the deck's edge",
                                s.target.distance, s.housing.margin)
                  : fmt::format("puts the board {:.3g} m from the deck's centre, within its {:.3g} m radius (housing.deck_radius): the "
                                "board would stand inside the deck; expected a board beyond the deck's edge",
                                board, s.deck_radius());
      if (target && target->has("distance")) throw target->error("distance", what);
      if (housing && housing->has(several ? "margin" : "deck_radius")) throw housing->error(several ? "margin" : "deck_radius", what);
      throw root.error("target", what);
    }
  }
  // A panel standing across the board's wall (at the board's height) takes its place there:
  // nails meeting it would bounce, not mark.
  if (housing) {
    const auto deflectors = housing->array_of_tables("deflectors");
    for (std::size_t i = 0; i < s.housing.deflectors.size() && i < deflectors.size(); ++i) {
      const DeflectorSpec& d = s.housing.deflectors[i];
      if (d.bottom < s.target_top() && d.top > s.target.bottom && deflector_crosses_board(s, d))
        throw deflectors[i].error(d.along.empty() ? "radius" : "along",
                                  "stands the panel across the board's wall, at the board's height: nails meeting it there would "
                                  "bounce, not mark; expected a panel inside the board (or beyond it)");
    }
  }
  // A board whose bottom is above the counted height: nails passing under it there would be
  // counted by SAE J232 but meet no board.
  if (s.target.bottom > s.counted_height() + 1e-6) {
    const std::string what = fmt::format("the board's bottom at {:.4g} m is above the counted height ({:.4g} m): nails passing under "
                                         "it would be counted by SAE J232 but meet no board; expected a bottom at or below it",
                                         s.target.bottom, s.counted_height());
    if (target && target->has("bottom")) throw target->error("bottom", what);
    throw root.error("target", what);
  }
  const auto zone = root.table("operator_zone");
  if (zone && s.zone.kind == OperatorZoneSpec::Kind::Sector) {
    // A zone wholly off the board, or wholly below the counted height, could never be hit:
    // its criteria could not fail.
    const double low = std::max(s.target.bottom, s.counted_height());
    if (!(s.zone.bottom < s.target_top() - 1e-6 && s.zone.top > low + 1e-6))
      throw zone->error(s.zone.bottom >= s.target_top() - 1e-6 ? "bottom" : "top",
                        fmt::format("the operator zone ({:.4g} to {:.4g} m) lies wholly {} (the board: {:.4g} to {:.4g} m; counted "
                                    "from {:.4g} m): no counted mark could fall in it; expected a zone on the board's counted part",
                                    s.zone.bottom, s.zone.top, s.zone.bottom >= s.target_top() - 1e-6 ? "above the board" : "below the counted part of the board",
                                    s.target.bottom, s.target_top(), s.counted_height()));
  }
}

// The seat outside the blades, a nail that fits the feed, and a board with a counted part.
void check_seat_feed_and_counted_board(const TableReader& root, const Scenario& s) {
  // A seat over a blade's disc is a seat inside the deck (a mesh deck's too).
  if (!s.field.present && s.zone.kind == OperatorZoneSpec::Kind::Derived) {
    const auto zone = root.table("operator_zone");
    for (std::size_t k = 0; k < s.spindles.size(); ++k) {
      const SpindleSpec& sp = s.spindles[k];
      const double off = std::hypot(s.zone.seat_x - sp.x, s.zone.seat_y - sp.y), tip = sp.blade.tip_radius();
      if (off < tip) {
        const std::string what = fmt::format("puts the operator's seat ({:.3g}, {:.3g}) m over {} blade, {:.3g} m from its axis "
                                             "within its {:.3g} m tip circle: inside the deck; expected a seat outside it",
                                             s.zone.seat_x, s.zone.seat_y, s.spindles.size() > 1 ? fmt::format("spindle {}'s", k + 1) : "the",
                                             off, tip);
        if (zone && zone->has("seat_x")) throw zone->error("seat_x", what);
        if (zone && zone->has("seat_y")) throw zone->error("seat_y", what);
        throw root.error("operator_zone", what);
      }
    }
  }
  // A nail wider than the feed's tube cannot drop through it.
  if (!s.field.present && s.feed.outlet_diameter > 0 && s.nail.diameter >= s.feed.outlet_diameter) {
    const auto feed = root.table("feed");
    const std::string what = fmt::format("the nail ({:.4g} m thick) cannot drop through the feed's outlet ({:.4g} m); expected an "
                                         "outlet wider than the nail",
                                         s.nail.diameter, s.feed.outlet_diameter);
    if (feed && feed->has("outlet_diameter")) throw feed->error("outlet_diameter", what);
    if (auto nail = root.table("nail"); nail && nail->has("diameter")) throw nail->error("diameter", what);
    throw root.error("feed", what);
  }
  // A board that cannot carry a counted mark is no test (its top within a micrometre of the
  // counted height, as the same height written in two units gives, included).
  if (!s.field.present && !(s.target_top() > s.counted_height() + 1e-6)) {
    const auto target = root.table("target");
    const std::string what = fmt::format("the board's top at {:.4g} m is at or below the counted height ({:.4g} m: {}); no mark on it "
                                         "could count, so the test could not fail; expected a top above it",
                                         s.target_top(), s.counted_height(),
                                         s.criteria.counted_height ? "criteria.counted_height" : "the blade tip circle's plane");
    if (target && target->has("top")) throw target->error("top", what);
    throw root.error("target", what);
  }
}

void check_consistency(const TableReader& root, Scenario& s) {
  check_blades(root, s);
  check_swept_discs(root, s);
  check_deck_plate(root, s);
  check_board(root, s);
  check_seat_feed_and_counted_board(root, s);
}
}  // namespace

double Scenario::blade_plane() const {
  double h = 0;
  for (const auto& sp : spindles) h = std::max(h, sp.geometry.height);
  return h;
}
double Scenario::reach() const {
  double r = 0;
  for (const auto& sp : spindles) r = std::max(r, sp.reach());
  return r;
}
double Scenario::lowest_blade_face() const {
  double h = HUGE_VAL;
  for (const auto& sp : spindles) h = std::min(h, sp.geometry.height - 0.5 * sp.geometry.thickness);
  return h;
}
std::optional<double> Scenario::front_gap() const {
  if (!meshes.empty()) return std::nullopt;
  double gap = housing.skirt_bottom;
  for (const auto& op : housing.openings)
    if (op.azimuth.contains(0.0)) gap = std::max(gap, housing.opening_top(op));
  return gap;
}
double Scenario::lifted_up_to(const FieldObjectSpec& o, double drag_coefficient, double u) const {
  return 3 * air.density * drag_coefficient * u * u / (4 * o.density * units::standard_gravity);
}

double Scenario::tip_speed() const {
  double v = 0;
  for (const auto& sp : spindles) v = std::max(v, sp.blade.omega * sp.blade.tip_radius());
  return v;
}

FeedStation Scenario::feed_station(std::size_t i) const {
  if (feed.stations) return feed.stations->at(i);
  return {i, std::max(0.0, spindles.at(i).blade.tip_radius() - 0.0508), 0.0};
}

std::vector<FeedStation> Scenario::feed_stations() const {
  std::vector<FeedStation> out;
  for (std::size_t i = 0; i < feed_station_count(); ++i) out.push_back(feed_station(i));
  return out;
}

bool CriteriaSpec::limits_depart_from_j232() const {
  const CriteriaSpec j232;
  return hits_zone != j232.hits_zone || punctures_zone != j232.punctures_zone || hits_outside != j232.hits_outside ||
         punctures_outside != j232.punctures_outside;
}

Scenario read_scenario(const std::string& file) { return read_scenario(parse_toml_file(file), file); }

Scenario read_scenario(const toml::table& document, const std::string& file) {
  TableReader root(document, file, "");
  Scenario s;
  s.file = file;
  s.title = root.string_or("title", std::filesystem::path(file).stem().string(), {});

  read_spindles(root, s.spindles);
  const double reach = s.reach();

  if (auto r = root.table("restitution")) s.restitution = read_restitution(*r);
  if (auto n = root.table("nail")) read_nail(*n, s.nail);
  if (auto f = root.table("feed")) read_feed(*f, s.feed, s.spindles);

  if (auto h = root.table("housing")) read_housing(*h, s.housing, s.spindles.size() > 1, s.notes);
  if (s.deck_radius() <= reach)
    throw root.table("housing")->error("deck_radius", fmt::format("expected a deck wider than the blade's tip circle ({:.4g} m)", reach));

  if (auto g = root.table("ground")) read_ground(*g, s.ground, root.has("field"));

  if (auto t = root.table("target")) read_target(*t, s);

  const auto base = std::filesystem::path(file).parent_path();
  for (const auto& m : root.array_of_tables("meshes", 32)) s.meshes.push_back(read_mesh_file(m, base, s.notes));

  refuse_what_meshes_replace(root, s.meshes);

  if (auto z = root.table("operator_zone")) read_zone(*z, s.zone);
  if (auto b = root.table("board")) read_board(*b, s.board);
  if (auto c = root.table("criteria")) read_criteria(*c, s.criteria);
  if (auto a = root.table("air")) read_air(*a, s.air);
  if (auto r = root.table("run")) read_run(*r, s.run);
  if (auto c = root.table("contacts")) {
    s.run.contact_model = c->string_or("model", "sequential", {"sequential", "simultaneous"}) == "simultaneous" ? ContactModel::Simultaneous
                                                                                                             : ContactModel::Sequential;
    s.run.blade_push = c->string_or("blade_push", "held", {"held", "impacts"}) == "impacts" ? BladePush::Impacts : BladePush::Held;
    c->refuse_unknown_keys();
  }
  if (auto f = root.table("field")) {
    refuse_test_rig(root, s.meshes);
    read_field(*f, s, root.has("restitution"), s.field, s.notes);
  }
  if (auto u = root.table("uncertainty")) {
    read_uncertainty(*u, s.uncertainty);
    // A field's assessments simulate objects; a J232 test's, replicates of the test.
    if (s.field.present && u->has("replicates"))
      throw u->error("replicates", "a field scenario's uncertainty study simulates objects at each draw, not replicates of the J232 test; "
                                   "expected objects = N instead");
    if (!s.field.present && u->has("objects"))
      throw u->error("objects", "only a field scenario ([field]) simulates objects; a J232 test's study takes replicates = N");
  }
  for (const auto& key : root.strings("estimates")) {
    const auto value = root.value_at(key);
    if (!value)
      throw root.error("estimates", fmt::format("\"{}\" names no value of this scenario; expected dotted keys of values it sets, "
                                                "such as \"housing.skirt_bottom\" or \"blade.speed\"",
                                                key));
    s.estimates.push_back({key, *value});
  }
  root.refuse_unknown_keys();
  check_consistency(root, s);
  return s;
}

}  // namespace j232::scenario
