// `j232 trace`: one nail of an assessment replayed with its whole trail (as pbrt's
// --debugstart replays one pixel): how it was fed, the feed's strike, and every event of
// its flight with the nail's state after it. Nails are pure functions of the seed, the
// replicate and their number, so the replay is the nail of the run: marks.csv's
// `replicate` and `nail` columns name it, or --find picks the first of a kind.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include <tbb/parallel_for.h>

#include "assess/simulator.hpp"
#include "flight/face_touch.hpp"
#include "flight/flight_audit.hpp"
#include "field/field_simulator.hpp"
#include "field/hazard_tally.hpp"
#include "cli/commands.hpp"
#include "cli/run_options.hpp"
#include "cli/exit_codes.hpp"
#include "report/atomic_file.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario_reader.hpp"
#include "units/quantity.hpp"
#include "report/result_files.hpp"

namespace j232::cli {
namespace {

struct TraceOptions {
  std::string scenario, find, json;
  std::uint64_t replicate = 0;
  int nail = 0;
  std::optional<std::uint64_t> object;  // a field scenario's object
  std::optional<std::uint64_t> seed;
  bool check = false;
  int check_count = 0;  // replicates (J232) or objects (field) to audit; 0: the default
};

// `j232 trace --check`: every nail of the first replicates (or the first objects of a field)
// replayed and audited (flight/flight_audit.hpp): along every stretch of its motion the
// capsule against every face of the scene, and every bounce's energy. Exits 1 when a capsule
// reaches more than 0.1 mm into a face or a bounce creates energy.
int check(const TraceOptions& o, const scenario::Scenario& s) {
  struct One {
    flight::FlightAudit audit;
    std::uint64_t replicate = 0;
    int nail = 0;
    bool cut_by_bounces = false, cut_off = false;
    flight::CutOff why = flight::CutOff::None;
    double in_soil = 0;
  };
  std::vector<One> ones;
  std::string unit;
  if (s.field.present) {
    const field::FieldSimulator sim(s);
    const int objects = o.check_count > 0 ? o.check_count : 2000;
    ones.resize(static_cast<std::size_t>(objects));
    tbb::parallel_for(0, objects, [&](int i) {
      std::vector<flight::FlightEvent> events;
      std::vector<flight::FlightStretch> stretches;
      const field::ObjectOutcome out = sim.simulate(static_cast<std::uint64_t>(i), nullptr, &events, &stretches);
      One& one = ones[static_cast<std::size_t>(i)];
      // Placed where it lies: pressed into the soil by its embedment, maybe under a chain curtain.
      one.audit = flight::audit_flight(sim.mower().scene().soup(), out.encounter.body, stretches, events, 8, true);
      one.in_soil = one.audit.placed_depth;
      one.nail = i;
      one.cut_off = out.flight.fate == flight::Fate::CutOff;
      one.why = out.flight.cut_off;
      one.cut_by_bounces = out.flight.cut_off == flight::CutOff::MaxBounces;
    });
    unit = "objects";
  } else {
    const assess::Simulator sim(s);
    const int replicates = o.check_count > 0 ? o.check_count : 2;
    const int count = replicates * s.feed.nails;
    ones.resize(static_cast<std::size_t>(count));
    tbb::parallel_for(0, count, [&](int i) {
      One& one = ones[static_cast<std::size_t>(i)];
      one.replicate = static_cast<std::uint64_t>(i / s.feed.nails), one.nail = i % s.feed.nails;
      const assess::NailReplay r = sim.replay(one.replicate, one.nail);
      one.audit = flight::audit_flight(sim.scene().soup(), r.drop.nail, r.stretches, r.events);
      one.cut_off = r.outcome.flight.fate == flight::Fate::CutOff;
      one.why = r.outcome.flight.cut_off;
      one.cut_by_bounces = r.outcome.flight.cut_off == flight::CutOff::MaxBounces;
    });
    unit = "nails";
  }
  flight::FlightAudit all;
  const One* worst = nullptr;
  int failing = 0, cut_off = 0, cut_by_bounces = 0;
  double deepest_soil = 0;
  for (const One& one : ones) {
    deepest_soil = std::max(deepest_soil, one.in_soil);
    all.merge(one.audit);
    if (!worst || one.audit.deepest > worst->audit.deepest) worst = &one;
    failing += one.audit.passed() ? 0 : 1;
    cut_off += one.cut_off, cut_by_bounces += one.cut_by_bounces;
  }
  fmt::print("{}\naudit of {} {} (seed {}): {} poses of the capsule against every face of the scene\n", s.title, ones.size(), unit,
             s.run.seed, all.poses);
  if (worst && all.deepest > 0)
    fmt::print("deepest overlap: {:.4f} mm into {} (face {}), {} {} at {:.3f} ms (limit {:.1f} mm)\n", 1e3 * all.deepest,
               scene::name(all.deepest_label), all.deepest_face + 1,
               s.field.present ? "object" : fmt::format("replicate {}, nail", worst->replicate), worst->nail, 1e3 * all.deepest_time,
               1e3 * flight::kAuditOverlap);
  else
    fmt::print("no pose overlaps a face\n");
  if (deepest_soil > 0)
    fmt::print("(a field's object starts where it lies, pressed into the soil by its embedment or under a chain curtain draped over it, "
               "up to {:.1f} mm in here: only what lies deeper in those faces than it started, or in any other face, counts)\n",
               1e3 * deepest_soil);
  fmt::print("bounces creating energy: {}{}\n", all.energy_gains,
             all.energy_gains ? fmt::format(" (largest {:.3g} J)", all.largest_gain) : std::string());
  std::array<int, flight::kCutOffReasons> by_reason{};
  for (const One& one : ones)
    if (one.cut_off) ++by_reason[static_cast<std::size_t>(one.why)];
  std::string reasons;
  for (int k = 1; k < flight::kCutOffReasons; ++k)
    if (by_reason[static_cast<std::size_t>(k)])
      reasons += fmt::format("{}{} {}", reasons.empty() ? ": " : ", ", by_reason[static_cast<std::size_t>(k)],
                             flight::cut_off_name(static_cast<flight::CutOff>(k)));
  fmt::print("cut off: {} ({} by the bounce cap){}\n", cut_off, cut_by_bounces, reasons);
  fmt::print("{}: {} of {} {} failed the audit\n", failing ? "FAILED" : "passed", failing, ones.size(), unit);
  return failing ? kFails : kOk;
}

// What --find looks for: each kind by its name and its test on a nail's outcome.
struct FindKind {
  const char* name;
  bool (*matches)(const assess::NailOutcome&);
};
constexpr FindKind kFindKinds[] = {
    {"puncture-zone", [](const assess::NailOutcome& o) { return o.flight.punctures_zone > 0; }},
    {"hit-zone", [](const assess::NailOutcome& o) { return o.flight.hits_zone > 0; }},
    {"puncture", [](const assess::NailOutcome& o) { return o.flight.punctures_zone + o.flight.punctures_outside > 0; }},
    {"mark", [](const assess::NailOutcome& o) { return o.flight.fate == flight::Fate::MarkedBoard; }},
    {"cut-off", [](const assess::NailOutcome& o) { return o.flight.fate == flight::Fate::CutOff; }},
    {"contained", [](const assess::NailOutcome& o) { return o.flight.fate == flight::Fate::Contained; }},
    {"stopped-by-guard", [](const assess::NailOutcome& o) { return o.flight.fate == flight::Fate::StoppedByGuard; }},
    {"over-board", [](const assess::NailOutcome& o) { return o.flight.fate == flight::Fate::OverBoard; }},
    {"short-of-board", [](const assess::NailOutcome& o) { return o.flight.fate == flight::Fate::ShortOfBoard; }},
    {"restruck", [](const assess::NailOutcome& o) { return o.flight.strikes > 1; }},
};
std::string find_kind_names() {
  std::string names;
  for (const auto& k : kFindKinds) names += (names.empty() ? "" : ", ") + std::string(k.name);
  return names;
}

// --find cut-off:REASON: a cut-off by that limit ("cut-off:wedged"); nullopt when the kind is
// not of that form; a clear error when REASON names no limit.
std::optional<flight::CutOff> cut_off_reason(const std::string& find) {
  const std::string prefix = "cut-off:";
  if (find.rfind(prefix, 0) != 0) return std::nullopt;
  std::string names;
  for (int c = 1; c < flight::kCutOffReasons; ++c) {
    const auto reason = static_cast<flight::CutOff>(c);
    if (find.substr(prefix.size()) == flight::cut_off_name(reason)) return reason;
    names += (names.empty() ? "" : ", ") + std::string(flight::cut_off_name(reason));
  }
  throw scenario::InputError("", std::nullopt, "--find", find, "expected cut-off:REASON with REASON one of " + names);
}

// After a fate on the trace's last line: the limit that cut the flight off, " (wedged)", or
// nothing.
std::string cut_off_suffix(const flight::FlightResult& f) {
  return f.fate == flight::Fate::CutOff ? fmt::format(" ({})", flight::cut_off_name(f.cut_off)) : std::string();
}

std::string vec(const flight::Vec3& v, int digits = 3) { return fmt::format("({:.{}f}, {:.{}f}, {:.{}f})", v.x(), digits, v.y(), digits, v.z(), digits); }

std::string detail(const flight::FlightEvent& e) {
  using Kind = flight::FlightEvent::Kind;
  switch (e.kind) {
    case Kind::Strike: return fmt::format("spindle {} edge {}", e.spindle + 1, e.edge + 1);
    case Kind::Push: return fmt::format("held on spindle {} edge {}, pressed at {:.0f} m/s2", e.spindle + 1, e.edge + 1, e.pressed);
    case Kind::Bounce:
    case Kind::GuardPass: {
      std::string what(scene::name(e.surface));
      if (e.surface == scene::Surface::Guard) what = fmt::format("guard {}", e.guard + 1);
      return fmt::format("{} (face {}), normal {}{}", what, e.face + 1, vec(e.normal, 2),
                         e.together > 1 ? fmt::format(", {} points together", e.together) : "");
    }
    case Kind::Board:
      return fmt::format("{}: {:.2f} J over {:.1f} mm -> {}", scene::name(e.surface), e.energy, 1e3 * e.width,
                         e.mark == 2 ? "puncture" : e.mark == 1 ? "hit" : "no mark");
    case Kind::LeftDeck: return fmt::format("crossed the outline at {}, azimuth {:.1f} deg", vec(e.point), std::atan2(e.point.y(), e.point.x()) / units::degree);
    case Kind::End: return flight::fate_name(e.fate);
    case Kind::Slide:
    case Kind::Rest: return "";
  }
  return "";
}

nlohmann::json event_json(const flight::FlightEvent& e) {
  auto v = [](const flight::Vec3& x) { return nlohmann::json::array({x.x(), x.y(), x.z()}); };
  nlohmann::json j{{"event", e.gentle ? "touch" : flight::event_name(e.kind)}, {"time_s", e.time},   {"centre_m", v(e.centre)},
                   {"velocity_m_s", v(e.velocity)},       {"spin_rad_s", v(e.spin)}, {"axis", v(e.axis)},
                   {"speed_before_m_s", e.speed_in}};
  using Kind = flight::FlightEvent::Kind;
  if (e.kind == Kind::Strike || e.kind == Kind::Bounce || e.kind == Kind::Board || e.kind == Kind::GuardPass)
    j["point_m"] = v(e.point), j["normal"] = v(e.normal);
  if (e.kind == Kind::Bounce || e.kind == Kind::Board || e.kind == Kind::GuardPass) j["surface"] = scene::name(e.surface), j["face"] = e.face + 1;
  if (e.kind == Kind::Strike || e.kind == Kind::Push) j["spindle"] = e.spindle + 1, j["edge"] = e.edge + 1;
  if (e.kind == Kind::Push) j["pressed_m_s2"] = e.pressed;
  if (e.kind == Kind::Bounce && e.together > 1) j["points_together"] = e.together;
  if (e.kind == Kind::Board)
    j["energy_J"] = e.energy, j["presented_width_m"] = e.width, j["mark"] = e.mark == 2 ? "puncture" : e.mark == 1 ? "hit" : "none";
  if (e.kind == Kind::LeftDeck) j["crossing_m"] = v(e.point);
  if (e.kind == Kind::End) j["fate"] = flight::fate_name(e.fate);
  return j;
}

// The trail as a table, an event a line.
void print_trail(const std::vector<flight::FlightEvent>& events) {
  fmt::print("{:>10}  {:<10}  {:<26}  {:>9}  {:>9}  {}\n", "t (ms)", "event", "centre after (m)", "v (m/s)", "w (rad/s)", "detail");
  for (const auto& e : events)
    fmt::print("{:>10.3f}  {:<10}  {:<26}  {:>9.2f}  {:>9.0f}  {}\n", 1e3 * e.time, e.gentle ? "touch" : flight::event_name(e.kind), vec(e.centre),
               e.velocity.norm(), e.spin.norm(), detail(e));
}

// One object of a field scenario (j232 hazard) with its whole trail. --find looks among the
// scenario's field.objects_simulated objects: cut-off, restruck, contained, thrown; hazardous
// (a hazardous ground impact beyond the deck, or a hazardous crossing of a plane, as the
// hazard run counts them); plane:NAME (one that crossed the plane NAME).
int trace_object(const TraceOptions& o, const scenario::Scenario& s) {
  const field::FieldSimulator sim(s);
  std::uint64_t index = o.object.value_or(0);
  if (!o.find.empty()) {
    // The hazard run's own watch says what an object did beyond the deck.
    field::HazardTally tally(field::HazardLayout::of(s.field));
    field::ObjectWatch watch(tally);
    std::optional<std::size_t> plane;
    if (o.find.rfind("plane:", 0) == 0) {
      std::string names;
      for (std::size_t p = 0; p < s.field.planes.size(); ++p) {
        if (s.field.planes[p].name == o.find.substr(6)) plane = p;
        names += (names.empty() ? "" : ", ") + s.field.planes[p].name;
      }
      if (!plane)
        throw scenario::InputError("", std::nullopt, "--find", o.find,
                                   names.empty() ? std::string("expected a plane of the scenario's [[field.planes]]; it has none")
                                                 : "expected plane:NAME with NAME one of the scenario's planes: " + names);
    }
    const bool hazardous = o.find == "hazardous";
    const std::optional<flight::CutOff> reason = cut_off_reason(o.find);
    auto matches = [&](const field::ObjectOutcome& out) {
      if (o.find == "cut-off") return out.fate == field::ObjectFate::CutOff;
      if (reason) return out.fate == field::ObjectFate::CutOff && out.flight.cut_off == *reason;
      if (o.find == "restruck") return out.fate == field::ObjectFate::Thrown && out.flight.strikes > 1;
      if (o.find == "contained") return out.flight.fate == flight::Fate::Contained;
      if (o.find == "thrown") return out.fate == field::ObjectFate::Thrown;
      if (plane) return watch.plane_crossings().at(*plane) > 0;
      if (hazardous) {
        bool any = watch.hazardous_impacts() > 0;
        for (const auto h : watch.plane_hazards()) any |= h > 0;
        return any;
      }
      throw scenario::InputError("", std::nullopt, "--find", o.find,
                                 "expected, for a field scenario, one of cut-off, cut-off:REASON, restruck, contained, thrown, hazardous, plane:NAME");
    };
    bool found = false;
    for (std::uint64_t i = 0; i < static_cast<std::uint64_t>(s.field.objects_simulated) && !found; ++i) {
      const field::ObjectOutcome out = sim.simulate(i, &watch);
      watch.finish(out);
      if (matches(out)) index = i, found = true;
    }
    if (found) fmt::print("the first object of the kind {}: object {}\n", o.find, index);
    if (!found) {
      fmt::print("no object of the {} of \"{}\" (seed {}) is of the kind {}\n", s.field.objects_simulated, s.title, s.run.seed, o.find);
      return kOk;
    }
  }
  std::vector<flight::FlightEvent> events;
  const field::ObjectOutcome out = sim.simulate(index, nullptr, &events);
  const auto& e = out.encounter;
  fmt::print("{}\nobject {} (seed {}); times on the blades' clock, positions in metres in the mower's frame\n", s.title, index, s.run.seed);
  fmt::print("{} '{}': {:.1f} mm, {:.1f} g, {:.3f} m across the cut, centre {:.1f} mm above the turf{}\n",
             s.field.objects[e.kind].kind == scenario::FieldObjectSpec::Kind::SteelBall ? "steel ball" : "stone", s.field.objects[e.kind].name,
             1e3 * e.body.diameter, 1e3 * e.body.mass, e.lateral, 1e3 * e.height,
             e.lifted ? std::string(" (lifted by the updraft)")
                      : e.support > 0 ? fmt::format(" (resting {:.1f} mm up, on what holds it: field.support_height)", 1e3 * e.support) : std::string());
  fmt::print("{}: thrown at {:.2f} m/s (ground frame), elevation {:.1f} deg; {:.2f} m/s off its last blade strike\n",
             field::object_fate_name(out.fate), out.exit_speed, out.launch_elevation / units::degree, out.last_strike_speed);
  print_trail(events);
  const auto& f = out.flight;
  fmt::print("fate: {}{}; {} strike(s) ({} in its longest pass), {} bounce(s), {} gentle contact(s)\n", flight::fate_name(f.fate),
             cut_off_suffix(f), f.strikes,
             f.strikes ? f.most_contacts_in_pass : 0, f.bounces, f.gentle_contacts);
  if (!o.json.empty()) {
    nlohmann::json j{{"program", "j232 trace"}, {"scenario", s.title}, {"seed", s.run.seed}, {"object", index},
                     {"fate", field::object_fate_name(out.fate)}, {"events", nlohmann::json::array()}};
    for (const auto& ev : events) j["events"].push_back(event_json(ev));
    report::write_atomically(o.json, report::json_text(j, 1) + "\n");
    fmt::print("wrote {}\n", o.json);
  }
  return kOk;
}

int run(const TraceOptions& o) {
  if (o.check) {
    scenario::Scenario s = scenario::read_scenario(o.scenario);
    if (o.seed) s.run.seed = *o.seed;
    return check(o, s);
  }
  if (const scenario::Scenario s = scenario::read_scenario(o.scenario); s.field.present) {
    scenario::Scenario with_seed = s;
    if (o.seed) with_seed.run.seed = *o.seed;
    return trace_object(o, with_seed);
  }
  if (o.object) throw scenario::InputError("", std::nullopt, "--object", std::to_string(*o.object), "only a field scenario ([field]) has objects; replay a nail with --replicate and --nail");
  const FindKind* find = nullptr;
  for (const auto& k : kFindKinds)
    if (o.find == k.name) find = &k;
  const std::optional<flight::CutOff> reason = cut_off_reason(o.find);
  if (!o.find.empty() && !find && !reason)
    throw scenario::InputError("", std::nullopt, "--find", o.find, "expected one of " + find_kind_names() + ", cut-off:REASON");
  scenario::Scenario s = scenario::read_scenario(o.scenario);
  if (o.seed) s.run.seed = *o.seed;
  if (o.nail < 0 || o.nail >= s.feed.nails)
    throw scenario::InputError("", std::nullopt, "--nail", std::to_string(o.nail), fmt::format("expected a nail from 0 to {} (the test feeds {})", s.feed.nails - 1, s.feed.nails));
  const assess::Simulator sim(s);
  std::uint64_t replicate = o.replicate;
  int nail = o.nail;
  if (find || reason) {
    // The first such nail in the order of the run (replicate, then nail).
    auto matches = [&](const assess::NailOutcome& out) {
      return find ? find->matches(out) : out.flight.fate == flight::Fate::CutOff && out.flight.cut_off == *reason;
    };
    bool found = false;
    for (std::uint64_t r = 0; r < static_cast<std::uint64_t>(s.run.replicates) && !found; ++r)
      for (int n = 0; n < s.feed.nails && !found; ++n)
        if (matches(sim.simulate(r, n))) replicate = r, nail = n, found = true;
    if (!found) {
      fmt::print("no nail of the {} replicates of \"{}\" (seed {}) is of the kind {}\n", s.run.replicates, s.title, s.run.seed, o.find);
      return kOk;
    }
  }
  const assess::NailReplay r = sim.replay(replicate, nail);
  const auto& d = r.drop;
  fmt::print("{}\nreplicate {}, nail {} (seed {}); times on the blades' clock, positions in metres from the deck's centre\n", s.title,
             replicate, nail, s.run.seed);
  fmt::print("fed at station {} (spindle {}): tip at ({:.3f}, {:.3f}) m from the spindle's axis, axis {}, falling {:.2f} m/s, blade at {:.1f} deg\n",
             d.station + 1, r.outcome.spindle + 1, d.position.x(), d.position.y(), vec(d.axis, 2), d.fall_speed,
             d.blade_phase / units::degree);
  if (!r.struck) {
    fmt::print("not struck: {}\n", flight::fate_name(r.outcome.flight.fate));
  } else {
    fmt::print("struck at {:.3f} ms by edge {} at {:.3f} m from the axis: {:.2f} m/s -> {:.2f} m/s, spin {:.0f} rad/s; contact {}, normal {}\n",
               1e3 * r.strike.time, r.strike.edge + 1, r.strike.radius, r.falling.norm(), r.velocity_after.norm(), r.spin_after.norm(),
               vec(r.strike.point), vec(r.strike.normal, 2));
    print_trail(r.events);
  }
  const auto& f = r.outcome.flight;
  fmt::print("fate: {}{}; {} strike(s) ({} in its longest pass), {} bounce(s), {} gentle contact(s), {} counted mark(s) (hits {} / "
             "punctures {} in the zone, hits {} / punctures {} outside)\n",
             flight::fate_name(f.fate), cut_off_suffix(f), f.strikes, f.strikes ? f.most_contacts_in_pass : 0, f.bounces, f.gentle_contacts, f.mark_count - f.uncounted_marks, f.hits_zone, f.punctures_zone,
             f.hits_outside, f.punctures_outside);
  if (f.trace.exit != flight::Exit::Inside) fmt::print("left the deck: {}\n", sim.exit_name(f.trace.exit, f.trace.exit_index));
  if (f.trace.first_exit != flight::Exit::Inside &&
      (f.trace.first_exit != f.trace.exit || f.trace.first_exit_index != f.trace.exit_index))
    fmt::print("first left by: {}{}\n", sim.exit_name(f.trace.first_exit, f.trace.first_exit_index),
               f.trace.exit == flight::Exit::Inside ? " (and came back in)" : "");
  if (!o.json.empty()) {
    nlohmann::json j{{"program", "j232 trace"},
                     {"scenario", s.title},
                     {"seed", s.run.seed},
                     {"replicate", replicate},
                     {"nail", nail},
                     {"station", d.station + 1},
                     {"struck", r.struck},
                     {"fate", flight::fate_name(f.fate)},
                     {"events", nlohmann::json::array()}};
    for (const auto& e : r.events) j["events"].push_back(event_json(e));
    report::write_atomically(o.json, report::json_text(j, 1) + "\n");
    fmt::print("wrote {}\n", o.json);
  }
  return kOk;
}
}  // namespace

Runner add_trace_command(CLI::App& app) {
  auto o = std::make_shared<TraceOptions>();
  CLI::App* cmd = app.add_subcommand("trace", "Replay one nail of an assessment (or one object of a field scenario) with its whole trail: its feed, strike and every contact");
  cmd->add_option("scenario", o->scenario, "Scenario file (TOML)")->required();
  add_unsigned_option(*cmd, "--replicate", o->replicate, "Replicate (0-based, as marks.csv numbers them)");
  cmd->add_option("--nail", o->nail, "Nail within the replicate (0-based, as marks.csv numbers them)");
  add_unsigned_option(*cmd, "--object", o->object, "A field scenario's object (0-based, as j232 hazard numbers them)");
  cmd->add_option("--find", o->find, "Replay the first nail of the run of this kind instead: " + find_kind_names() +
                                         ", cut-off:REASON (a limit as result.json names it: cut-off:wedged)"
                                         " (a field scenario: cut-off, cut-off:REASON, restruck, contained, thrown, hazardous, plane:NAME)");
  add_unsigned_option(*cmd, "--seed", o->seed, "Random seed (overrides the scenario's [run] seed)");
  cmd->add_option("--json", o->json, "Also write the trail as JSON to this file");
  cmd->add_flag("--check", o->check,
                "Audit instead: replay every nail of the first replicates (a field: the first objects) and check the capsule against "
                "every face of the scene along its whole path (no overlap beyond 0.1 mm) and every bounce's energy; exits 1 if any fails");
  cmd->add_option("--count", o->check_count, "With --check: how many replicates (default 2) or field objects (default 2000)")->check(CLI::PositiveNumber);
  return [o] { return run(*o); };
}

}  // namespace j232::cli
