#include "flight/nail_flight.hpp"

#include <boost/random/normal_distribution.hpp>
#include <algorithm>
#include <cmath>

#include "board/board.hpp"
#include "flight/plane_touch.hpp"
#include "strike/impulse.hpp"
#include "units/quantity.hpp"

namespace j232::flight {

const char* fate_name(Fate f) {
  switch (f) {
    case Fate::NotStruck: return "not_struck";
    case Fate::Contained: return "contained_by_housing";
    case Fate::StoppedByGuard: return "stopped_by_guard";
    case Fate::ReachedBoardUnmarked: return "reached_board_unmarked";
    case Fate::MarkedBoard: return "marked_board";
    case Fate::MarkedBelowCountedHeight: return "marked_below_counted_height";
    case Fate::OverBoard: return "over_board";
    case Fate::ShortOfBoard: return "at_rest_short_of_board";
    case Fate::CutOff: return "cut_off";
  }
  return "unknown";
}

const char* cut_off_name(CutOff c) {
  switch (c) {
    case CutOff::None: return "none";
    case CutOff::TimeLimit: return "time_limit";
    case CutOff::MaxBounces: return "max_bounces";
    case CutOff::FlightSteps: return "flight_step_cap";
    case CutOff::MaxStrikes: return "strike_cap";
    case CutOff::SearchSteps: return "contact_search_step_cap";
    case CutOff::ContactsInPass: return "contacts_per_pass_cap";
    case CutOff::UnresolvedContact: return "unresolved_blade_contact";
    case CutOff::NonFinite: return "non_finite_state";
  }
  return "unknown";
}

const char* touch_name(Touch t) {
  switch (t) {
    case Touch::Blade: return "blade";
    case Touch::Housing: return "housing";
    case Touch::Deflector: return "deflector";
    case Touch::GuardBounce: return "guard";
    case Touch::GuardPass: return "guard-pass";
    case Touch::Ground: return "ground";
    case Touch::Board: return "board";
  }
  return "unknown";
}

const char* event_name(FlightEvent::Kind k) {
  switch (k) {
    case FlightEvent::Kind::Strike: return "strike";
    case FlightEvent::Kind::Bounce: return "bounce";
    case FlightEvent::Kind::GuardPass: return "guard-pass";
    case FlightEvent::Kind::Slide: return "slide";
    case FlightEvent::Kind::Rest: return "rest";
    case FlightEvent::Kind::Board: return "board";
    case FlightEvent::Kind::LeftDeck: return "left-deck";
    case FlightEvent::Kind::End: return "end";
  }
  return "unknown";
}

namespace {

bool in_arc(double a, double from, double to) {
  double span = units::wrap_angle(to - from);
  if (span == 0) span = units::two_pi;  // from == to: the whole turn
  return units::wrap_angle(a - from) < span;
}

constexpr int kSustainedContacts = 64;   // contacts in one pass before a field's object counts as pushed along
constexpr double kSustainedGap = 1e-5;   // s between the last two of them
constexpr double kSlideBelow = 0.5;  // m/s: a rebound weaker than this does not leave the ground
constexpr double kMaxChord = 0.5;    // m
constexpr double kLift = 0.002;      // m: a sliding nail's centre above the ground

// Restitution along the normal n (facing the incoming nail), Coulomb friction along the surface.
Vec3 bounce(const Vec3& v, const Vec3& n, double e, double mu) {
  const double vn = v.dot(n);  // < 0: approaching
  if (vn >= 0) return v;
  const Vec3 tangential = v - vn * n;
  const double vt = tangential.norm();
  const double slip = mu * (1 + e) * (-vn);  // friction impulse per unit mass, at most stopping the slip
  const Vec3 t_after = vt > slip ? Vec3(tangential * (1 - slip / vt)) : Vec3::Zero();
  return t_after - e * vn * n;
}

// The normal tilted by a random angle (roughness) about a random axis in the surface.
Vec3 rough_normal(const Vec3& n, double roughness, random::Stream& rng) {
  if (roughness <= 0) return n;
  boost::random::normal_distribution<double> tilt(0.0, roughness);
  const double angle = tilt(rng);
  const double psi = units::two_pi * rng.uniform();
  Vec3 u = n.unitOrthogonal();
  const Vec3 w = n.cross(u);
  const Vec3 axis = std::cos(psi) * u + std::sin(psi) * w;
  return (n * std::cos(angle) + axis.cross(n) * std::sin(angle)).normalized();
}

}  // namespace

namespace {

// One nail's flight from its first strike to its end: the state its steps share. The
// steps are the chord (advance, blades, scene), what a surface does (respond), sliding on
// the ground (slide), where it left the deck (moved) and its fate.
struct NailFlight {
  const Body& start;
  const projectile::Projectile& nail;
  const Drag& drag;
  const FlightContext& ctx;
  const strike::BladePhases& phases;
  const FirstContact& first;
  random::EventDraws& draws;
  const double length = nail.length, diameter = nail.diameter, mass = nail.mass;
  const FlightSettings& set = *ctx.settings;

  FlightResult r{};
  Body b = start;
  scene::Skip skip{};
  bool last_contact_guard = false;
  bool ended_at_rest = false;
  // A knife riding over an object pressed into the soil (a field's stone) touches it no
  // more in that pass: its spindle's contacts before `ridden_until` are passed over.
  std::size_t ridden_spindle = first.spindle;
  double ridden_until = first.ridden_until;
  void ride_over(std::size_t spindle, double time) {
    ++r.ridden_over;
    ridden_spindle = spindle;
    ridden_until = time + kRideOverTurn / (*ctx.spindles)[spindle].omega();
  }
  bool at_board = false;
  bool cut_off = false;
  // Cut off by `why` (the first limit reached is the one named).
  void cut(CutOff why) {
    if (!cut_off) r.cut_off = why;
    cut_off = true;
  }
  // The pass under way: its spindle and edge, when it last touched, its contacts; and
  // whether the nail has yet to leave the blade (it has touched nothing else since it was fed).
  std::size_t pass_spindle = first.spindle, pass_edge = first.edge;
  double last_contact = start.time;
  int pass_contacts = 1;
  bool on_blade = true;
  Touch last_touch = Touch::Blade;
  std::uint16_t last_guard_passed = 0;
  double last_event = start.time;  // the last contact with anything (blade or scene)
  bool in_deck = ctx.deck_outline && !ctx.deck_outline->empty() && ctx.deck_outline->contains(b.position.x(), b.position.y());

  FlightResult run();
  // The flight's events (run() loops over them).
  struct Chord {
    DragOverStep drag;
    Vec3 accel;
    double dt;
    Body next;
    Vec3 step;
    double len;
    strike::Motion motion;
  };
  struct NextEvent {
    enum class Kind { ChordEnd, Blade, PlaneAgain, Surface };
    Kind kind = Kind::ChordEnd;
    std::optional<strike::Contact> contact;
    std::optional<PlaneTouch> again;
    std::optional<scene::Hit> hit;
    std::optional<PlaneTouch> touch;  // the capsule's first touch of the hit's plane (none: the centre's arrival)
  };
  bool event_check(double t_end, int& steps);
  bool carried();
  void observe(const Chord& c, const NextEvent& e) const;
  Chord event_advance(double t_end) const;
  NextEvent event_find(const Chord& c);
  bool event_collide(const Chord& c, const NextEvent& e);
  // An event of the replayed nail (nothing unless the context collects them), the nail's
  // state as it now is.
  FlightEvent* log(FlightEvent::Kind kind, const Vec3& point = Vec3::Zero(), const Vec3& normal = Vec3::Zero(), double speed_in = 0) {
    if (!ctx.events) return nullptr;
    FlightEvent e;
    e.kind = kind, e.time = b.time, e.centre = b.position, e.velocity = b.velocity, e.spin = b.spin, e.axis = b.axis;
    e.point = point, e.normal = normal, e.speed_in = speed_in;
    ctx.events->push_back(e);
    return &ctx.events->back();
  }
  void touch(Touch t) {
    r.trace.touch(t);
    last_touch = t;
  }
  // `along`: where the chord's straight segment (the centre's ray, which decided what the
  // nail met) is at that time, when `to` is off it (up to the chord's sag).
  void moved(const Vec3& from, const Vec3& to, const Vec3* along = nullptr);
  void leave_deck(const Vec3& from, const Vec3& to);
  std::optional<strike::Contact> blade_contact(const strike::Motion& chord, double until);
  Vec3 meet(const PlaneTouch& at, const Chord& chord);
  void restrike(const strike::Contact& k);
  void touched_scene() { on_blade = false; }
  void close_pass() {
    ++r.passes_by_contacts[std::min(static_cast<std::size_t>(pass_contacts), r.passes_by_contacts.size()) - 1];
  }
  void record_mark(const Vec3& point, double energy, bool zone, bool puncture);
  void reach_board(const scene::Hit& hit, const PlaneTouch& at, const Vec3& velocity);
  std::optional<PlaneTouch> surface_touch(const scene::Hit& hit, const strike::Motion& chord, double centre_arrives, double until) const;
  std::optional<PlaneTouch> plane_touch(const scene::Hit& hit, const strike::Motion& chord, double from, double until) const;
  // `arm`: the touching point from the centre (in flight; null: the nail slides on the
  // ground and bounces as a point).
  bool respond(const scene::Hit& hit, const Vec3* arm = nullptr);
  void bounce_off(const Vec3& n, double e, double mu, const Vec3* arm, double surface_inverse_mass = 0.0);
  bool slide(const scene::Hit& hit);
  bool after_bounce(const scene::Hit& hit);
  std::optional<scene::Hit> last_plane{};  // the surface last bounced off (not a guard passed through)
  Fate fate() const;
};

// The nail moved straight from `from` to `to`: if that took it out of the deck's outline,
// where and how (a guard it had just passed, an opening, under the skirt, over the deck);
// if back in, it has not left yet. The last crossing out is the way out; the first is kept.
void NailFlight::moved(const Vec3& from, const Vec3& to_centre, const Vec3* along) {
  NailTrace& trace = r.trace;
  if (ctx.path) ctx.path->push_back(to_centre);
  if (!ctx.deck_outline || ctx.deck_outline->empty()) return;
  // Where it left is judged on the segment the scene was queried along, so that a centre
  // whose ray passed under the skirt's edge is not said to have gone through it.
  const Vec3& to = along ? *along : to_centre;
  const bool inside = ctx.deck_outline->contains(to.x(), to.y());
  if (!in_deck) {
    // Back inside the outline (turned back by a guard, or over the plate and down): it has
    // not left, until it crosses again.
    if (inside) in_deck = true, trace.exit = Exit::Inside, trace.exit_index = 0;
    return;
  }
  if (inside) return;
  in_deck = false;
  leave_deck(from, to);
  if (trace.first_exit == Exit::Inside) trace.first_exit = trace.exit, trace.first_exit_index = trace.exit_index;
}

// The crossing of the deck's outline going out between `from` and `to`: where, and what it
// went through.
void NailFlight::leave_deck(const Vec3& from, const Vec3& to) {
  NailTrace& trace = r.trace;
  const Vec3 c = from + ctx.deck_outline->exit_fraction(from, to) * (to - from);
  log(FlightEvent::Kind::LeftDeck, c);
  trace.exit_index = 0;
  trace.exit_azimuth = std::atan2(c.y(), c.x());
  trace.exit_height = c.z();
  if (last_touch == Touch::GuardPass) {
    trace.exit = Exit::Guard;
    trace.exit_index = last_guard_passed;
    return;
  }
  if (c.z() >= ctx.deck_top) {
    trace.exit = Exit::OverDeck;
    return;
  }
  if (!ctx.generated_deck) {
    trace.exit = Exit::DeckEdge;
    return;
  }
  const auto& openings = set.openings;
  for (std::size_t i = 0; i < openings.size(); ++i)
    if (c.z() < openings[i].top && in_arc(trace.exit_azimuth, openings[i].azimuth_from, openings[i].azimuth_to)) {
      trace.exit = Exit::Opening;
      trace.exit_index = static_cast<std::uint16_t>(i);
      return;
    }
  if (c.z() < ctx.skirt_bottom + 1e-9) {
    trace.exit = Exit::UnderSkirt;
    return;
  }
  // Through the skirt's height outside every opening's azimuths (beside a chute, along its
  // side wall): the nearest opening's.
  trace.exit = Exit::DeckEdge;
  double nearest = HUGE_VAL;
  for (std::size_t i = 0; i < openings.size(); ++i)
    for (double edge : {openings[i].azimuth_from, openings[i].azimuth_to}) {
      const double d = std::abs(std::remainder(trace.exit_azimuth - edge, units::two_pi));
      if (d < nearest) nearest = d, trace.exit = Exit::Opening, trace.exit_index = static_cast<std::uint16_t>(i);
    }
}

// The nail over a chord as the contact searches see it: its centre moving with the chord's
// starting velocity and acceleration, its axis turning with its spin.
strike::Motion chord_motion(const Body& from, const Vec3& acceleration) {
  strike::Motion m;
  m.p0 = from.position, m.v0 = from.velocity, m.a = acceleration, m.t0 = from.time, m.axis0 = from.axis, m.spin = from.spin;
  return m;
}

// A surface met where the centre meets it (a nail sliding on the ground, or no touch found).
PlaneTouch centre_touching(const Body& b, const Vec3& point) {
  PlaneTouch at;
  at.time = b.time, at.centre = b.position, at.axis = b.axis, at.point = point;
  return at;
}

// The earliest blade contact of the nail moving as `chord` until `until`.
std::optional<strike::Contact> NailFlight::blade_contact(const strike::Motion& m, double until) {
  std::optional<strike::Contact> best;
  if (!ctx.spindles) return best;
  strike::SearchStats stats;
  for (std::size_t k = 0; k < ctx.spindles->size(); ++k) {
    const strike::Spindle& sp = (*ctx.spindles)[k];
    const auto method = sp.reference_search ? strike::SearchMethod::FixedSteps : strike::SearchMethod::Advancement;
    auto c = strike::first_contact(sp, phases.at_zero[k], nail, m, best ? best->time : until, stats, method);
    // A knife that rode over the object in this pass: its next touch after it has gone by.
    if (c && k == ridden_spindle && c->time < ridden_until) {
      c.reset();
      if (ridden_until < (best ? best->time : until)) {
        strike::Motion later = m;
        later.p0 = m.centre(ridden_until), later.v0 = m.velocity(ridden_until), later.axis0 = m.axis(ridden_until), later.t0 = ridden_until;
        c = strike::first_contact(sp, phases.at_zero[k], nail, later, best ? best->time : until, stats, method);
      }
    }
    if (c && (!best || c->time < best->time)) best = c, best->spindle = k;
  }
  r.search_steps += stats.steps;
  if (stats.gave_up) cut(CutOff::SearchSteps);
  return best;
}

// Struck again: the contact's impulse gives the new velocity and spin.
void NailFlight::restrike(const strike::Contact& k) {
  NailTrace& trace = r.trace;
  const strike::Spindle& sp = (*ctx.spindles)[k.spindle];
  const strike::StrikeOutcome out = strike::strike(sp, k, nail, b.velocity, b.spin);
  if (!out.approaching) {  // the search found a touch the impulse cannot resolve: never loop on it
    cut(CutOff::UnresolvedContact);
    return;
  }
  // The same pass while the same edge touches again within a quarter turn and nothing else
  // came between.
  const bool same_pass = k.spindle == pass_spindle && k.edge == pass_edge && last_touch == Touch::Blade &&
                         (k.time - last_contact) * sp.omega() < 0.5 * units::pi;
  if (same_pass) {
    ++pass_contacts;
  } else {
    close_pass();
    pass_contacts = 1;
    ++r.passes;
  }
  r.most_contacts_in_pass = std::max(r.most_contacts_in_pass, pass_contacts);
  if (pass_contacts > FlightResult::kMaxContactsPerPass) cut(CutOff::ContactsInPass);
  // A field's heavy object pushed along by the blade (sustained contact): the impulses come
  // ever closer together without end as the turning plate keeps catching it. Past
  // kSustainedContacts contacts in a pass, the last within kSustainedGap, it moves with the
  // blade's point there (a sticking contact) and leaves along that point's path.
  const bool sustained = set.soil_under_strikes && same_pass && pass_contacts > kSustainedContacts && k.time - last_contact < kSustainedGap;
  pass_spindle = k.spindle, pass_edge = k.edge, last_contact = k.time, last_event = k.time;
  const double speed_in = ctx.events ? b.velocity.norm() : 0.0;  // for a replay's trail only
  b.velocity = out.velocity_after;
  if (set.soil_under_strikes &&
      soil_reaction(b.position, nail.half_segment() + nail.radius(), set.materials.of(scene::Surface::Ground, 0).friction, set.ground_velocity,
                    b.velocity) &&
      (b.velocity + out.spin_after.cross(k.point - b.position) - sp.velocity_at(k.point)).dot(k.normal) <= 0)
    ride_over(k.spindle, k.time);
  // The spin about the nail's own axis (from friction at its surface) is left out: it
  // holds under 1/200 of the energy of its tumbling, and flight follows the axis only.
  b.spin = out.spin_after - out.spin_after.dot(b.axis) * b.axis;
  if (sustained) b.velocity = sp.velocity_at(k.point), b.spin = Vec3::Zero(), ++r.pushed_along;
  if (on_blade) r.launch_velocity = b.velocity;  // its launch: the last contact before it touches anything else
  ++r.strikes;
  touch(Touch::Blade);
  trace.last_strike_speed = b.velocity.norm();
  last_contact_guard = false;
  if (FlightEvent* e = log(FlightEvent::Kind::Strike, k.point, k.normal, speed_in))
    e->spindle = static_cast<std::uint16_t>(k.spindle), e->edge = static_cast<std::uint16_t>(k.edge);
}

void NailFlight::record_mark(const Vec3& point, double energy, bool zone, bool puncture) {
  const bool counted = point.z() >= ctx.counted_height;
  if (r.mark_count < FlightResult::kMaxMarks) r.marks[static_cast<std::size_t>(r.mark_count)] = {point, energy, zone, puncture, counted};
  ++r.mark_count;
  if (!counted)
    ++r.uncounted_marks;
  else
    (zone ? (puncture ? r.punctures_zone : r.hits_zone) : (puncture ? r.punctures_outside : r.hits_outside)) += 1;
}

// Where the tumbling nail first touches the surface it is heading for: the centre's ray met
// it at `centre_arrives`; the capsule reached its plane earlier, by up to half its
// length, at the point its spin had turned nearest (docs/model.md §5.5). Searched from
// the time the centre was that far from the plane, but never before the chord's start:
// what happened before it is history (its events are told), and a capsule already on the
// plane there meets it there.
std::optional<PlaneTouch> NailFlight::surface_touch(const scene::Hit& hit, const strike::Motion& chord, double centre_arrives,
                                                    double until) const {
  const double closing = std::max(1e-3, -hit.normal.dot(chord.velocity(centre_arrives)));
  const double reach = nail.half_segment() + nail.radius() + 1e-3;
  return plane_touch(hit, chord, std::max(chord.t0, centre_arrives - 2 * reach / closing), std::min(centre_arrives, until));
}

// The capsule's first touch of the plane of `hit` within [from, until].
std::optional<PlaneTouch> NailFlight::plane_touch(const scene::Hit& hit, const strike::Motion& chord, double from, double until) const {
  // The plane it last bounced off (its face or a face beside it in that plane): the touch it
  // is leaving is no new one.
  const bool same_plane = last_plane && last_plane->normal.dot(hit.normal) > 1 - 1e-12 &&
                          std::abs(hit.normal.dot(hit.point - last_plane->point)) < 1e-9;
  return first_plane_touch(chord, nail, hit.point, hit.normal, from, until, same_plane);
}

// The nail moved along the chord to where it touches a surface; returns the touching
// point from its centre.
Vec3 NailFlight::meet(const PlaneTouch& at, const Chord& chord) {
  const Vec3 from = b.position;
  const Vec3 on_segment = from + chord.step * std::clamp((at.time - b.time) / chord.dt, 0.0, 1.0);
  b.position = at.centre, b.velocity = chord.motion.velocity(at.time), b.axis = at.axis, b.time = at.time;
  moved(from, b.position, &on_segment);
  last_event = b.time;
  return at.point - at.centre;
}

// The board judges the point that strikes it (docs/model.md §5.5): the energy a plastic
// impact there takes out of the rod, m_eff v_n^2 / 2 with v_n that point's speed into the
// board (its centre's and its spin's) and m_eff the rod's mass felt there along the
// normal; the width the rod presents; the mark where that point is, in the zone (or not)
// that the board is labelled with there.
void NailFlight::reach_board(const scene::Hit& hit, const PlaneTouch& at, const Vec3& velocity) {
  const Vec3& n = hit.normal;
  const Vec3 arm = at.point - at.centre;
  const double approach = std::max(0.0, -n.dot(velocity + b.spin.cross(arm)));
  const double at_point = 0.5 * effective_mass(nail, at.axis, arm, n) * approach * approach;
  // A nail nearly flat has more of its shank within the crush depth than its end: the part
  // pressing on the board shares what a plastic contact along the whole shank takes out (its
  // normal translation and the turn that moves its ends along n), in proportion to its length.
  const double cos_theta = std::abs(at.axis.dot(n));
  const double pressing = cos_theta * length > set.board.crush_depth ? set.board.crush_depth / cos_theta : length;
  const double centre_in = std::max(0.0, -n.dot(velocity)), turn = n.dot(b.spin.cross(at.axis));
  const double along_shank = centre_in > 0 ? 0.5 * mass * centre_in * centre_in + 0.5 * nail.transverse_inertia() * turn * turn : 0.0;
  const double energy = std::max(at_point, pressing / length * along_shank);
  const double width = board::presented_width(length, diameter, at.axis.dot(n), set.board.crush_depth);
  const board::Mark mark = board::classify(energy, width, set.board);
  if (r.board_energy < 0) r.board_energy = energy, r.board_energy_per_width = energy / width;
  if (mark != board::Mark::None) {
    // The board's label where the mark is (the centre's face when the point overhangs the
    // board's edge), or a derived zone's line of sight from the blade that threw the nail.
    bool zone = hit.surface == scene::Surface::TargetZone;
    ++r.queries;
    const auto there = ctx.scene->first_hit(at.point + 1e-3 * n, -n, 2e-3);
    if (there && (there->surface == scene::Surface::TargetZone || there->surface == scene::Surface::TargetOutside))
      zone = there->surface == scene::Surface::TargetZone;
    if (ctx.zone && ctx.spindles && pass_spindle < ctx.spindles->size()) {
      const auto& sp = (*ctx.spindles)[pass_spindle];
      zone = ctx.zone->contains(at.point, Vec3(sp.centre.x(), sp.centre.y(), sp.height));
    }
    record_mark(at.point, energy, zone, mark == board::Mark::Puncture);
  }
  if (FlightEvent* e = log(FlightEvent::Kind::Board, at.point, n, velocity.norm())) {
    e->surface = hit.surface, e->face = hit.face, e->energy = energy, e->width = width;
    e->mark = mark == board::Mark::Puncture ? 2 : mark == board::Mark::Hit ? 1 : 0;
  }
  // The board is the test's catcher: a nail that does not go through it drops at its foot.
  touch(Touch::Board);
  at_board = true;
}

// What the surface at `hit` does to the nail arriving as `b`. Returns false when the nail stops.
// A bounce with restitution e and friction mu off the surface with normal n: at the touching
// point as a rigid body when there is one, else at the centre.
// A surface that gives (a flap on its hinge) has the inverse of its mass at the contact.
void NailFlight::bounce_off(const Vec3& n, double e, double mu, const Vec3* arm, double surface_inverse_mass) {
  // A touching point that does not move into the surface while the centre does (found on
  // the plane already): the centre's bounce, so that no surface is crossed.
  if (arm && (b.velocity + b.spin.cross(*arm)).dot(n) < 0)
    rebound(nail, b.axis, *arm, n, e, mu, b.velocity, b.spin, surface_inverse_mass);
  else if (surface_inverse_mass > 0 && b.velocity.dot(n) < 0)
    rebound(nail, b.axis, Vec3::Zero(), n, e, mu, b.velocity, b.spin, surface_inverse_mass);
  else
    b.velocity = bounce(b.velocity, n, e, mu);
}

bool NailFlight::respond(const scene::Hit& hit, const Vec3* arm) {
  const SurfaceMaterial& material = set.materials.of(hit.surface, hit.guard);
  const Vec3 n = hit.normal;
  const double speed_in = ctx.events ? b.velocity.norm() : 0.0;  // for a replay's trail only
  // How the surface meets the nail: its touching point's velocity (the centre's when it slides).
  const Vec3 v_in = arm ? Vec3(b.velocity + b.spin.cross(*arm)) : b.velocity;
  switch (material.response) {
    case SurfaceMaterial::Response::Board:
      // Reached sliding along the ground (in flight, run() finds the touch first): at the
      // point where the centre meets it, lying as it lies.
      reach_board(hit, centre_touching(b, hit.point), b.velocity);
      return false;
    case SurfaceMaterial::Response::Curtain:
      if (random::Stream pass = draws.next(random::Purpose::GuardPass); pass.uniform() < material.openness) {
        b.velocity *= material.pass_speed_factor;  // slips between the links, losing speed
        touch(Touch::GuardPass);
        last_guard_passed = hit.guard;
        if (FlightEvent* e = log(FlightEvent::Kind::GuardPass, hit.point, n, v_in.norm())) e->surface = hit.surface, e->face = hit.face, e->guard = hit.guard;
        return true;
      }
      break;  // else it bounces off the curtain
    case SurfaceMaterial::Response::Flap:
    case SurfaceMaterial::Response::Bounce: break;
  }
  if (ctx.observer && hit.surface == scene::Surface::Ground)
    ctx.observer->met_ground(b.time, arm ? Vec3(b.position + *arm) : hit.point, b.velocity, in_deck);
  // The facet the nail meets: on a rough surface the local normal, tilted at random; one it
  // would meet from behind is no facet it can meet, and is drawn again.
  Vec3 facet = n;
  if (material.roughness > 0) {
    random::Stream rng = draws.next(random::Purpose::Roughness);  // this bounce's, and its redraws
    facet = rough_normal(n, material.roughness, rng);
    for (int tries = 0; tries < 16 && v_in.dot(facet) >= 0; ++tries) facet = rough_normal(n, material.roughness, rng);
    if (v_in.dot(facet) >= 0) facet = n;
  }
  // The impact angle against that facet (turf's restitution follows it) or the normal speed.
  double angle = 0.5 * units::pi;
  if (material.by_angle) {
    const double speed = v_in.norm();
    if (speed > 0) angle = std::asin(std::clamp(-v_in.dot(facet) / speed, 0.0, 1.0));
  }
  // A flap swings about its hinge: at the contact's depth below it, it moves as a mass
  // I / d^2 along its normal (at rest before the impact: it is taken to have swung back
  // between one nail's contacts, a stated simplification).
  const double contact_height = arm ? b.position.z() + arm->z() : hit.point.z();
  const double give = material.response == SurfaceMaterial::Response::Flap ? 1.0 / material.flap_mass_at(contact_height) : 0.0;
  bounce_off(facet, material.restitution(std::max(-v_in.dot(n), 1e-9), angle), material.friction, arm, give);
  // A rough facet cannot send a point-like bounce into the surface. (A tumbling rod's centre
  // may still move into it after a rigid rebound at one end: its next touch is searched.)
  if (material.roughness > 0) {
    const double out = b.velocity.dot(n);
    if (out < 0 && !arm) b.velocity -= 2 * out * n;
  }
  switch (hit.surface) {
    case scene::Surface::Housing: touch(Touch::Housing); break;
    case scene::Surface::Deflector: touch(Touch::Deflector); break;
    case scene::Surface::Guard: touch(Touch::GuardBounce); break;
    default: touch(Touch::Ground); break;
  }
  // Whether a nail that comes to rest under the mower was last turned back by a guard (a
  // bounce on the turf after it does not change that).
  if (hit.surface != scene::Surface::Ground) last_contact_guard = hit.surface == scene::Surface::Guard;
  ++r.bounces;
  if (FlightEvent* e = log(FlightEvent::Kind::Bounce, arm ? Vec3(b.position + *arm) : hit.point, n, speed_in))
    e->surface = hit.surface, e->face = hit.face, e->guard = hit.guard;
  return true;
}

// On the ground after `hit` with too little rebound to fly: slides to rest, or into a wall
// and on. Returns false when the flight has ended (at rest, stopped, cut off).
bool NailFlight::slide(const scene::Hit& hit) {
  const Vec3 up = hit.normal;
  const double decel = set.materials.of(hit.surface, hit.guard).friction * -kGravity.z();
  b.position -= up.dot(b.position - hit.point) * up;  // it lies on the ground (its centre was up to half its length above)
  log(FlightEvent::Kind::Slide, b.position, up, b.velocity.norm());
  bool stopped = false;
  while (!stopped) {
    Vec3 slide = b.velocity - b.velocity.dot(up) * up;
    const double speed = slide.norm();
    if (r.bounces > set.max_bounces || !std::isfinite(speed)) {
      cut(std::isfinite(speed) ? CutOff::MaxBounces : CutOff::NonFinite);
      break;
    }
    if (speed < set.rest_speed || decel <= 0) {
      ended_at_rest = true;
      log(FlightEvent::Kind::Rest, b.position, up);
      break;
    }
    slide /= speed;
    const double distance = speed * speed / (2 * decel);
    // Its centre slides just above the ground (a lying nail's), or a sphere's radius above it;
    // a sphere also looks for walls near its top, which meets a skirt's lower edge its centre
    // would pass under (a field's stone rolling at a deck).
    const double lift = std::max(kLift, nail.radius());
    const Vec3 from = b.position + lift * up;
    ++r.queries;
    auto wall = ctx.scene->first_hit(from, slide, distance, skip);
    if (nail.radius() > kLift) {
      ++r.queries;
      if (auto top = ctx.scene->first_hit(from + 0.9 * nail.radius() * up, slide, wall ? wall->distance : distance, skip)) wall = top;
    }
    const double t0 = b.time;
    if (!wall) {
      if (ctx.observer) ctx.observer->flew(t0, from, speed * slide, t0 + speed / decel, from + distance * slide, Vec3::Zero());
      moved(from, from + distance * slide);
      b.position = from + distance * slide;
      b.time += speed / decel;
      last_event = b.time;
      b.velocity = Vec3::Zero();
      ended_at_rest = true;
      log(FlightEvent::Kind::Rest, b.position, up);
      break;
    }
    const double arrive = std::sqrt(std::max(0.0, speed * speed - 2 * decel * wall->distance));
    b.time += (speed - arrive) / decel;
    last_event = b.time;
    const Vec3 at = from + wall->distance * slide;  // its centre where it meets the wall (the wall's point, for a lying nail)
    if (ctx.observer) ctx.observer->flew(t0, from, speed * slide, b.time, at, arrive * slide);
    moved(from, nail.radius() > kLift ? at : wall->point);
    b.position = nail.radius() > kLift ? at : wall->point;
    b.velocity = arrive * slide;
    skip = {};
    skip.add(wall->face);
    stopped = !respond(*wall);
    if (set.materials.of(wall->surface, wall->guard).holds_up) break;  // slid onto another ground face: fly on from there
  }
  return !(stopped || ended_at_rest || cut_off);
}

// After a bounce off `hit`: remembered for the tumbling nail's next touch of it; on the
// ground with too little rebound to fly, it slides to rest or into a wall and on; at rest
// only on something that holds it up (not under the deck plate, not on a wall). Returns
// false when the flight has ended.
bool NailFlight::after_bounce(const scene::Hit& hit) {
  if (last_touch != Touch::GuardPass) last_plane = hit;
  // How fast its ends swing about its centre: a nail still tumbling is not lying yet.
  const double swing = b.spin.norm() * nail.half_segment();
  if (set.materials.of(hit.surface, hit.guard).holds_up && b.velocity.dot(hit.normal) < kSlideBelow && swing < kSlideBelow) {
    last_plane.reset();
    b.spin = Vec3::Zero();  // lying on the ground, it slides without turning
    if (!slide(hit)) return false;
  }
  if (b.velocity.norm() < set.rest_speed && swing < set.rest_speed && hit.normal.z() > 0.5) {
    ended_at_rest = true;
    log(FlightEvent::Kind::Rest, b.position, hit.normal);
    return false;
  }
  return true;
}

// How the flight ended, in the tally's words.
Fate NailFlight::fate() const {
  const double horizontal = std::hypot(b.position.x(), b.position.y());
  if (r.mark_count > r.uncounted_marks)
    return Fate::MarkedBoard;
  else if (r.mark_count > 0)
    return Fate::MarkedBelowCountedHeight;
  else if (r.non_finite || (cut_off && !at_board))
    return Fate::CutOff;
  else if (at_board)
    return Fate::ReachedBoardUnmarked;
  else if (horizontal <= ctx.deck_radius && b.position.z() > -1.0)
    return last_contact_guard ? Fate::StoppedByGuard : Fate::Contained;
  else if (ended_at_rest && horizontal < ctx.board_near)
    return Fate::ShortOfBoard;
  else
    return Fate::OverBoard;
}

// Whether the flight goes on: its state is finite, within the run's limits, and still in
// the test's space. Sets what ended it.
bool NailFlight::event_check(double t_end, int& steps) {
  if (!b.position.allFinite() || !b.velocity.allFinite() || !std::isfinite(b.time)) {
    r.non_finite = true;
    cut(CutOff::NonFinite);
    return false;
  }
  if (b.time >= t_end || r.bounces > set.max_bounces || ++steps > kMaxFlightSteps || r.strikes > FlightResult::kMaxStrikes) {
    cut(b.time >= t_end              ? CutOff::TimeLimit
        : r.bounces > set.max_bounces ? CutOff::MaxBounces
        : steps > kMaxFlightSteps     ? CutOff::FlightSteps
                                      : CutOff::MaxStrikes);
    return false;
  }
  const double horizontal2 = b.position.x() * b.position.x() + b.position.y() * b.position.y();
  return !(horizontal2 > ctx.escape_radius * ctx.escape_radius || b.position.z() < -1.0);
}

// The next chord of free flight from where the nail is: the drag and acceleration shared by
// the chord's length, its step and a step to a hit on it; where it would end; and the
// motion the contact searches follow along it.
NailFlight::Chord NailFlight::event_advance(double t_end) const {
  const DragOverStep step_drag(drag, b);
  const Vec3 accel = step_drag.acceleration(b.velocity, b.axis);
  const double dt = std::min(chord_step(b, accel, set.chord_tolerance, kMaxChord, step_drag), t_end - b.time);
  const Body next = advance(b, dt, step_drag, accel);
  return {step_drag, accel, dt, next, next.position - b.position, (next.position - b.position).norm(), chord_motion(b, accel)};
}

// What ends the chord first: the blades, the surface the nail last bounced off met again
// by its other end or the same one as it tumbles (its face is skipped by the centre's ray
// just after the bounce), a surface the centre's ray meets, or nothing. The cheap queries
// go first, so that the blades are searched only up to the earliest of them: a tumbling
// nail's chords mostly end at a plane it touches again within a fraction of the chord.
NailFlight::NextEvent NailFlight::event_find(const Chord& c) {
  NextEvent e;
  const double chord_end = b.time + c.dt;
  ++r.queries;
  // The centre's ray looks beyond the chord's end by a few of the nail's reaches: a surface
  // met there is the chord's event when the tumbling capsule reaches its plane within the
  // chord (its end crosses a wall the centre has yet to reach), so that no part of the nail
  // is through a wall when its centre's ray finds it.
  const double look_ahead = 4 * (nail.half_segment() + nail.radius());
  e.hit = ctx.scene->first_hit(b.position, c.step / c.len, c.len + look_ahead, skip);
  // The centre meets the surface at the share of the chord's time its ray has travelled.
  double hit_time = chord_end;
  if (e.hit) {
    const double centre_arrives = b.time + c.dt * e.hit->distance / c.len;
    e.touch = surface_touch(*e.hit, c.motion, centre_arrives, chord_end);
    if (e.touch)
      hit_time = e.touch->time;
    else if (e.hit->distance <= c.len)
      hit_time = centre_arrives;  // (never expected: the centre reaching the plane means the capsule did)
    else
      e.hit.reset();  // beyond the chord, and not reached within it
  }
  if (last_plane && last_plane->normal.dot(b.position - last_plane->point) < nail.half_segment() + nail.radius() + c.len)
    e.again = first_plane_touch(c.motion, nail, last_plane->point, last_plane->normal, b.time, chord_end, true);
  if (e.again && !(e.again->time < hit_time)) e.again.reset();
  e.contact = blade_contact(c.motion, e.again ? e.again->time : hit_time);
  if (cut_off) return e;
  e.kind = e.contact ? NextEvent::Kind::Blade : e.again ? NextEvent::Kind::PlaneAgain : e.hit ? NextEvent::Kind::Surface : NextEvent::Kind::ChordEnd;
  return e;
}

// What the event does to the nail. Returns false when the flight has ended.
bool NailFlight::event_collide(const Chord& c, const NextEvent& e) {
  switch (e.kind) {
    case NextEvent::Kind::ChordEnd:
      moved(b.position, c.next.position);
      b = c.next;
      skip = {};
      return true;
    case NextEvent::Kind::PlaneAgain: {
      const scene::Hit plane = *last_plane;
      const Vec3 arm = meet(*e.again, c);
      return respond(plane, &arm) && after_bounce(plane);
    }
    case NextEvent::Kind::Blade: {
      const Vec3 from = b.position;
      b.position = e.contact->centre;
      b.velocity += c.accel * (e.contact->time - b.time);
      b.axis = e.contact->axis;
      b.time = e.contact->time;
      moved(from, b.position);
      skip = {};
      restrike(*e.contact);
      return !cut_off;
    }
    case NextEvent::Kind::Surface: break;
  }
  const scene::Hit& hit = *e.hit;
  touched_scene();
  // The capsule touches the surface's plane before its centre gets there (by up to half
  // its length), at the point its tumbling has turned nearest (found with the event).
  const double to_hit = c.dt * hit.distance / c.len;
  const auto& at = e.touch;
  if (set.materials.of(hit.surface, hit.guard).response == SurfaceMaterial::Response::Board) {
    if (at) {
      const Vec3 velocity = c.motion.velocity(at->time);
      meet(*at, c);
      reach_board(hit, *at, velocity);
      return false;
    }
    moved(b.position, hit.point);
    b = advance(b, to_hit, c.drag, c.accel);
    b.position = hit.point;
    reach_board(hit, centre_touching(b, hit.point), b.velocity);
    return false;
  }
  skip = {};
  skip.add(hit.face);
  if (at) {
    const Vec3 arm = meet(*at, c);
    if (!respond(hit, &arm)) return false;
  } else {  // (never expected: the centre reaching the plane means the capsule did)
    moved(b.position, hit.point);
    b = advance(b, to_hit, c.drag, c.accel);
    b.position = hit.point;
    last_event = b.time;
    if (!respond(hit)) return false;
  }
  return after_bounce(hit);
}

// At rest on turf that moves under the mower (a field): carried with it toward the deck's
// rear, until a blade reaches it (struck again: the flight goes on) or it has crossed the
// deck (it stays where it lies). Returns true when struck again.
bool NailFlight::carried() {
  const Vec3& turf = set.ground_velocity;
  const double speed = turf.norm();
  if (!(speed > 0) || !in_deck || !ctx.spindles) return false;
  strike::Motion m;
  m.p0 = b.position, m.v0 = turf, m.a = Vec3::Zero(), m.t0 = b.time, m.axis0 = b.axis, m.spin = Vec3::Zero();
  // Long enough to cross the whole deck (and no longer than the flight may last).
  const double until = std::min(b.time + 2 * ctx.deck_radius / speed, start.time + set.time_limit);
  const auto k = blade_contact(m, until);
  if (!k || cut_off) return false;
  const Vec3 from = b.position;
  b.position = k->centre, b.velocity = turf, b.spin = Vec3::Zero(), b.axis = k->axis, b.time = k->time;
  moved(from, b.position);
  skip = {};
  last_plane.reset();
  ended_at_rest = false;
  restrike(*k);
  return !cut_off;
}

// The free stretch from where the nail is to the event that ends the chord, told to the
// context's observer.
void NailFlight::observe(const Chord& c, const NextEvent& e) const {
  double t1 = c.next.time;
  Vec3 p1 = c.next.position, v1 = c.next.velocity;
  switch (e.kind) {
    case NextEvent::Kind::ChordEnd: break;
    case NextEvent::Kind::Blade: t1 = e.contact->time, p1 = e.contact->centre, v1 = c.motion.velocity(t1); break;
    case NextEvent::Kind::PlaneAgain: t1 = e.again->time, p1 = e.again->centre, v1 = c.motion.velocity(t1); break;
    case NextEvent::Kind::Surface:
      if (e.touch) {
        t1 = e.touch->time, p1 = e.touch->centre;
      } else {
        t1 = b.time + c.dt * e.hit->distance / c.len, p1 = e.hit->point;
      }
      v1 = c.motion.velocity(t1);
      break;
  }
  ctx.observer->flew(b.time, b.position, b.velocity, t1, p1, v1);
}

// The flight as a loop of named events (as OpenMC's event_advance / event_collide): check
// that it goes on, plan the next chord, find what ends it, and let that act on the nail.
FlightResult NailFlight::run() {
  r.trace.last_strike_speed = start.velocity.norm();
  r.launch_velocity = start.velocity;
  const double t_end = start.time + set.time_limit;
  int steps = 0;
  if (ctx.path) ctx.path->push_back(b.position);
  while (event_check(t_end, steps)) {
    const Chord c = event_advance(t_end);
    if (!(c.len > 1e-12)) {
      b = c.next;
      continue;
    }
    const NextEvent e = event_find(c);
    if (cut_off) break;
    if (ctx.observer) observe(c, e);
    if (!event_collide(c, e)) {
      if (ended_at_rest && !cut_off && carried()) continue;  // on moving turf, struck again
      break;
    }
  }
  close_pass();
  r.flight_time = b.time - start.time;
  r.end_position = b.position;
  r.fate = fate();
  if (FlightEvent* e = log(FlightEvent::Kind::End)) e->fate = r.fate;
  return std::move(r);
}

}  // namespace

FlightResult fly(const Body& start, const projectile::Projectile& nail, const Drag& drag, const FlightContext& ctx,
                 const strike::BladePhases& phases, const FirstContact& first, random::EventDraws& draws) {
  return NailFlight{start, nail, drag, ctx, phases, first, draws}.run();
}

}  // namespace j232::flight
