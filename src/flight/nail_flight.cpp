#include "flight/nail_flight.hpp"
#include "flight/board_strike.hpp"

#include <boost/random/normal_distribution.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "board/board.hpp"
#include "invariant/check.hpp"
#include "flight/face_touch.hpp"
#include "flight/launch.hpp"
#include "flight/penetration.hpp"
#include "flight/plane_touch.hpp"
#include "strike/impulse.hpp"
#include "units/arc.hpp"
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
    case CutOff::MaxStrikes: return "max_strikes";
    case CutOff::SearchSteps: return "contact_search_step_cap";
    case CutOff::ContactsInPass: return "max_contacts_per_pass";
    case CutOff::UnresolvedContact: return "unresolved_blade_contact";
    case CutOff::NonFinite: return "non_finite_state";
    case CutOff::MaxGentleContacts: return "max_gentle_contacts";
    case CutOff::Wedged: return "wedged";
    case CutOff::SankIntoFace: return "sank_into_face";
  }
  return "unknown";
}

const char* cut_off_setting(CutOff c) {
  switch (c) {
    case CutOff::None: return "none";
    case CutOff::TimeLimit: return "run.time_limit";
    case CutOff::MaxBounces: return "run.max_bounces";
    case CutOff::FlightSteps: return "the flight's step cap";
    case CutOff::MaxStrikes: return "run.max_strikes";
    case CutOff::SearchSteps: return "the contact searches' limits";
    case CutOff::ContactsInPass: return "run.max_contacts_per_pass";
    case CutOff::UnresolvedContact: return "a blade touch the impulse could not resolve";
    case CutOff::NonFinite: return "a non-finite state";
    case CutOff::MaxGentleContacts: return "run.max_gentle_contacts";
    case CutOff::Wedged: return "a wedge that contacts one at a time cannot resolve";
    case CutOff::SankIntoFace: return "a sustained contact the face search cannot follow";
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
    case FlightEvent::Kind::Push: return "push";
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

// A field's object touched by one edge in more contacts than this in one pass is counted as
// pushed along by an arm (a count for the report only: every contact of the push is
// resolved as it comes, docs/model.md §9.1).
constexpr int kPushedAlongContacts = 64;
// Contacts (strikes or bounces) each within kWedgeGap of the one before and each with another
// body than the one before (a knife, then a face; two faces of a corner; two knives),
// kWedgeContacts in a row: the nail is wedged, and the impacts, resolved one at a time,
// accumulate at one instant without end (a Zeno sequence; simultaneous contacts would resolve
// it). Touches of one face in quick succession (sliding along it) are no wedge. Between two
// knives, each strike may add energy (an independent review saw a nail pumped to 3.4 times the
// tip speed in 25 of them): kBladePinch such strikes in a row are a wedge already. A field's
// object pushed along by one knife meets one body, and is followed contact by contact.
constexpr int kWedgeContacts = 64;
constexpr int kBladePinch = 6;
constexpr double kWedgeGap = 1e-8;  // s
constexpr double kSlideBelow = 0.5;  // m/s: a rebound weaker than this does not leave the ground
constexpr int kMaxSlideParts = 10000;  // parts of one slide (a tenth of the speed each where drag counts: about 60 from 60 m/s)
constexpr double kRollingSlip = 1e-6;  // m/s: a ball whose contact slips slower than this rolls
constexpr double kSinksDeeper = 2.0;   // shank diameters: a nail sunk deeper stays (an estimate)
// m: the longest chord. Shorter chords sweep smaller boxes, so each face search inside a deck
// meets fewer faces: 0.15 m runs 13-17 % more nails a second than 0.5 m on the shipped J232
// decks and the same on the fields (docs/validation.md §4).
constexpr double kMaxChord = 0.15;
// A sphere held on a knife's face ([contacts] blade_push = "held"): each step of its slide
// turns the knife this far (at 990 rpm, 96 us: a push of a few ms takes a few dozen steps,
// each an RK4 step of the slide with the face put back exactly at its end), and it is let go
// when the face's clearance from it, measured on the real section, is more than this (it
// slid past the face's edge, or the face's plane no longer stands for the section there).
constexpr double kHeldTurn = 0.01;        // rad
constexpr double kHeldSlack = 5e-6;       // m
// A lying nail slides with its lowest point this far above the ground (clear of its faces by
// more than the touch tolerance, so that sliding along them is no touch).
constexpr double kLyingGap = 5 * kFaceTolerance;
// A slide pressed into a face of the mower by the moving turf is held by it only while its
// clearance to that face is below this (a touch is within kFaceTolerance; round-off in a part
// along the face stays far below 0.1 mm).
constexpr double kPressedGap = 1e-4;
// A face over a sliding object (its normal more than 60 deg down from the ground's up: a
// skirt's lower edge, the deck's underside) touched again within kWedgeGap: jammed under it.
constexpr double kCeilingSlope = 0.5;
// The faces a chord's search considers at most: a longer list halves the chord.
constexpr std::size_t kMaxCandidates = 256;

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
  // The approach speed below which a contact is gentle: a fall through the object's own
  // diameter, sqrt(2 g D) (0.22 m/s for a 6d nail).
  const double gentle_speed = std::sqrt(2 * -kGravity.z() * diameter);
  const FlightSettings& set = *ctx.settings;

  FlightResult r{};
  Body b = start;
  // The faces the chord's search considers (the broad phase's answer for the chord).
  std::array<std::uint32_t, kMaxCandidates> candidates{};
  std::size_t candidate_count = 0;
  // A guard's curtain the nail is passing through: its faces are not met until the capsule
  // is clear of them.
  int passing_guard = -1;
  // A field's object: how deep it started in the faces it lies pressed into (its face search's
  // cap on sinking is counted below that; FaceFilter::start_depths). Recorded by run().
  StartDepths start_depths{};
  bool in_field() const { return set.materials.ground().takes_strikes; }  // a field's ground takes strikes; a test's turf does not
  // A flap just struck at this instant: touched again at once (the object still pushing the
  // flap it set swinging), it is met as a rigid stop, not as its mass again.
  int struck_flap = -1;
  double struck_flap_time = -HUGE_VAL;
  bool last_contact_guard = false;
  bool ended_at_rest = false;
  bool held_by_mower = false;  // at rest pressed against a face of the mower, pushed along by it (not carried by the turf)
  // Contacts within kWedgeGap of the one before, in a row, and when the last was.
  // `body`: a face's number, or -1 - (the spindle's number * 64 + the edge's) for a knife.
  int wedge_contacts = 0, blade_pinch = 0;
  double last_any_contact = -HUGE_VAL;
  long long last_body = std::numeric_limits<long long>::min();
  void note_contact(double t, long long body) {
    if (!(t - last_any_contact < kWedgeGap)) {
      wedge_contacts = 0, blade_pinch = 0;
    } else if (body != last_body) {
      ++wedge_contacts;
      if (body < 0 && last_body < 0) ++blade_pinch;
    }
    last_any_contact = t, last_body = body;
    if (wedge_contacts >= kWedgeContacts || blade_pinch >= kBladePinch) cut(CutOff::Wedged);
  }
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
    enum class Kind { ChordEnd, Blade, Surface };
    Kind kind = Kind::ChordEnd;
    std::optional<strike::Contact> contact;
    std::optional<FaceTouch> touch;  // the capsule's first touch of a face of the scene
  };
  // The last event was a blade strike, at this instant (event_find looks there first).
  bool struck_now = false;
  // Every spindle's contact search is the fast one (strike::SearchMethod::Advancement).
  const bool fast_blade_search =
      ctx.spindles && std::none_of(ctx.spindles->begin(), ctx.spindles->end(), [](const strike::Spindle& sp) { return sp.reference_search; });
  bool event_check(double t_end, int& steps);
  bool carried();
  void observe(const Chord& c, const NextEvent& e) const;
  Chord event_advance(double t_end);
  // A sphere held on a knife's face ([contacts] blade_push = "held", docs/model.md §9.1): the
  // face is fixed in the blade's frame, so it is its normal when caught and the centre's
  // distance along it from the spindle's axis, turned with the blade. Held, the body slides on
  // the face under the knife's push, Coulomb friction against its slip there, gravity and
  // drag, until the push would pull (it lifts off), the real section no longer touches it
  // (past the face's edge or the arm's tip) or anything else is met. It skids: its spin is
  // not followed while held (a ball's spin-up on the knife is left out).
  struct Held {
    std::size_t spindle = 0, edge = 0;
    double t0 = 0;
    Vec3 normal0 = Vec3::UnitY();  // from the knife into the body, at t0
    double offset = 0;             // normal · (centre - the spindle's axis point at ground level)
  };
  std::optional<Held> held{};
  Vec3 held_normal(const Held& h, double t) const;
  Vec3 held_acceleration(const Held& h, const DragOverStep& over, const Vec3& c, const Vec3& v, double t, double& pressed) const;
  void hold(const strike::Contact& k);
  Chord held_chord(double t_end);
  void held_moved();
  Chord chord_from(const Body& from, double dt, const DragOverStep& drag, const Vec3& accel) const;
  std::size_t gather(const strike::Motion& m, double from, double until, bool counted = true);
  // The faces about the nail where it is now, at rest (not counted as a chord's query).
  void gather_here() {
    strike::Motion still;
    still.p0 = b.position, still.t0 = b.time, still.axis0 = b.axis;
    gather(still, b.time, b.time, false);
  }
  FaceFilter filter();
  scene::Hit face_hit(const FaceTouch& at) const;
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
  // The capsule's motion over [from, until], for an audit of the replay.
  void stretch(const strike::Motion& m, double from, double until) {
    if (ctx.stretches && until >= from) ctx.stretches->push_back({m, from, until});
  }
  // Kinetic (translational and rotational) and potential energy now, seen from a frame
  // moving at `frame` (a bounce's: the surface struck; the turf moves under a field's mower).
  double energy(const Vec3& frame = Vec3::Zero()) const {
    return 0.5 * mass * (b.velocity - frame).squaredNorm() + 0.5 * nail.transverse_inertia() * b.spin.squaredNorm() -
           mass * kGravity.z() * b.position.z();
  }
  // The velocity of a surface's material at a contact with normal n, in the mower's frame: the
  // turf's in a field (it moves under the travelling mower), zero for the mower's own faces and
  // in the J232 test. The scene's faces stand still in the mower's frame, so the turf moves
  // along them as a belt does: only its part across n, never into the object. A bounce is
  // resolved where that material is still: restitution on the approach to it, friction on the
  // slip over it (as the slide and the soil's reaction are).
  Vec3 surface_velocity(scene::Surface s, const Vec3& n) const {
    if (s != scene::Surface::Ground) return Vec3::Zero();
    const Vec3& turf = set.materials.ground().velocity;
    return turf - turf.dot(n) * n;
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
  void lie_down(const Vec3& up, const Vec3& on);
  void touched_scene() { on_blade = false; }
  void close_pass() {
    ++r.passes_by_contacts[std::min(static_cast<std::size_t>(pass_contacts), r.passes_by_contacts.size()) - 1];
  }
  void record_mark(const Vec3& point, double energy, bool zone, bool puncture);
  void reach_board(const scene::Hit& hit, const PlaneTouch& at, const Vec3& velocity);
  Vec3 meet(const FaceTouch& at, const Chord& chord);
  // `arm`: the touching point from the centre (in flight; null: the nail slides on the
  // ground and bounces as a point).
  bool respond(const scene::Hit& hit, const Vec3* arm = nullptr);
  bool respond_together(const FaceTouch& at);
  // `frame`: the velocity of the surface struck (its energies are seen from there).
  void bounced(const scene::Hit& hit, double approach, const Vec3& point, double speed_in, double energy_in, int together,
               const Vec3& frame);
  void bounce_off(const Vec3& n, double e, double mu, const Vec3* arm, double surface_inverse_mass = 0.0);
  bool slide(const scene::Hit& hit);
  // A nail meeting soil point-first (touching at an end, its axis within 45 deg of the
  // surface's inward normal, moving along it toward the point) that Young's equation sinks
  // deeper than two shank diameters stays there (docs/model.md §5.3a). Returns true when it did.
  bool sinks_in(const SurfaceMaterial& material, const Vec3& n, const Vec3& arm);
  // A sphere that rolls on the ground rather than skids (FlightContext::rolls).
  bool rolling() const { return ctx.rolls && nail.half_segment() == 0; }
  // A sphere that does not roll (an angular stone) does not roll along the mower's steel
  // either: its flats stop it. Each contact with a face of the mower is the rigid sphere's
  // (friction may spin it up, as far as the slip halting), and it leaves without that spin,
  // as its slide on the turf takes it. So a single bounce keeps the sphere's law, and a
  // sustained contact (a stone thrown round a deck's skirt, met as micro-impacts) skids,
  // friction taking mu of the skirt's push: before, such a stone rolled along the skirt for
  // seconds, losing almost nothing (docs/model.md §5.3). On the turf the slide does this.
  bool skids_on(scene::Surface surface) const { return !ctx.rolls && nail.half_segment() == 0 && surface != scene::Surface::Ground; }
  bool after_bounce(const scene::Hit& hit);
  std::optional<scene::Hit> lying_on_ground();
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
    if (c.z() < openings[i].top && openings[i].azimuth.contains(trace.exit_azimuth)) {
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
    for (double edge : {openings[i].azimuth.from, openings[i].azimuth.to}) {
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

// A face touch as the board and the nail's move take a touch: when, the capsule then, the point.
PlaneTouch as_touch(const FaceTouch& at) {
  PlaneTouch p;
  p.time = at.time, p.centre = at.centre, p.axis = at.axis, p.point = at.point;
  return p;
}

// The earliest blade contact of the nail moving as `chord` until `until`.
std::optional<strike::Contact> NailFlight::blade_contact(const strike::Motion& m, double until) {
  std::optional<strike::Contact> best;
  if (!ctx.spindles) return best;
  strike::SearchStats stats;
  for (std::size_t k = 0; k < ctx.spindles->size(); ++k) {
    if (held && k == held->spindle) continue;  // the body is on its face: the hold follows that contact
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
  held.reset();  // struck: whatever held it before lets go (hold() below may hold it again)
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
  if (pass_contacts > set.max_contacts_per_pass) cut(CutOff::ContactsInPass);
  // A field's object pushed along by the blade: each contact is resolved as it comes (a chain
  // of impacts, each with Coulomb friction in its impulse, is the sliding along the arm that
  // tests/cli/push_law_check.py fits); the report counts the objects so pushed.
  // (Held pushes, [contacts] blade_push = "held", are counted as each is caught.)
  if (set.materials.ground().takes_strikes && set.blade_push == scenario::BladePush::Impacts && pass_contacts == kPushedAlongContacts + 1)
    ++r.pushed_along;
  pass_spindle = k.spindle, pass_edge = k.edge, last_contact = k.time, last_event = k.time;
  const double speed_in = ctx.events ? b.velocity.norm() : 0.0;  // for a replay's trail only
  const SurfaceMaterial& ground = set.materials.ground();
  const StruckSoil soil{nail.half_segment() + nail.radius(), ground.friction, 0.0, ground.velocity};
  const AfterStrike left = after_strike(out, sp, k, b.position, ground.takes_strikes ? &soil : nullptr);
  if (left.ride_over) ride_over(k.spindle, k.time);
  b.velocity = left.velocity;
  b.spin = nail.without_axial_spin(left.spin, b.axis);
  if (on_blade) r.launch_velocity = b.velocity;  // its launch: the last contact before it touches anything else
  ++r.strikes;
  note_contact(k.time, -1 - static_cast<long long>(k.spindle * 64 + k.edge));
  touch(Touch::Blade);
  trace.last_strike_speed = b.velocity.norm();
  trace.last_strike_velocity = b.velocity;
  last_contact_guard = false;
  if (FlightEvent* e = log(FlightEvent::Kind::Strike, k.point, k.normal, speed_in))
    e->spindle = static_cast<std::uint16_t>(k.spindle), e->edge = static_cast<std::uint16_t>(k.edge);
  hold(k);
}

// A spindle's turning as a vector (rad/s, about +z), and its axis's point at ground level.
Vec3 spin_of(const strike::Spindle& sp) { return {0.0, 0.0, sp.sense * sp.omega()}; }
Vec3 axis_point(const strike::Spindle& sp) { return {sp.centre.x(), sp.centre.y(), 0.0}; }

// The held face's normal at t: the normal when caught, turned with the blade.
Vec3 NailFlight::held_normal(const Held& h, double t) const {
  const strike::Spindle& sp = (*ctx.spindles)[h.spindle];
  const units::SinCos sc = units::sin_cos(sp.sense * sp.omega() * (t - h.t0));
  const Vec3& n = h.normal0;
  return {sc.cos * n.x() - sc.sin * n.y(), sc.sin * n.x() + sc.cos * n.y(), n.z()};
}

// The held body's acceleration with its centre at c moving at v at time t: gravity and drag,
// the face's push `pressed` (per unit mass) along its normal n, and Coulomb friction mu times
// that against the slip. The push keeps n(t) . (c - o) fixed to second order (o on the
// spindle's axis, the blade turning at W): n . a + 2 (W x n) . v + (W x (W x n)) . (c - o) = 0.
Vec3 NailFlight::held_acceleration(const Held& h, const DragOverStep& over, const Vec3& c, const Vec3& v, double t, double& pressed) const {
  const strike::Spindle& sp = (*ctx.spindles)[h.spindle];
  const Vec3 n = held_normal(h, t), w = spin_of(sp);
  const Vec3 free = over.acceleration(v, b.axis), wn = w.cross(n);
  pressed = -n.dot(free) - 2.0 * wn.dot(v) - w.cross(wn).dot(c - axis_point(sp));
  // The slip: the body's velocity against the face's where they touch, across the normal.
  Vec3 slip = v - sp.velocity_at(c - nail.radius() * n);
  slip -= slip.dot(n) * n;
  const double slipping = slip.norm();
  // (Within a step the push may come out negative before the step's end lets the body go: a
  // face never pulls, nor does its friction then act.)
  const double push = std::max(pressed, 0.0);
  Vec3 a = free + push * n;
  if (slipping > 0) a -= sp.friction * push / slipping * slip;
  return a;
}

// Just struck: a sphere the knife would catch again before it could part from the face by
// the touch tolerance (its speed away from the face u with u^2 < 2 A delta, A the face's push
// toward it) is held there.
void NailFlight::hold(const strike::Contact& k) {
  if (set.blade_push != scenario::BladePush::Held || nail.half_segment() != 0 || cut_off) return;
  // A knife that rides over the object (pressed into the soil) does not push it.
  if (k.spindle == ridden_spindle && k.time < ridden_until) return;
  const strike::Spindle& sp = (*ctx.spindles)[k.spindle];
  Held h;
  h.spindle = k.spindle, h.edge = k.edge, h.t0 = k.time, h.normal0 = k.normal;
  const Vec3 o = axis_point(sp), w = spin_of(sp);
  h.offset = k.normal.dot(b.position - o);
  double pressed = 0;
  held_acceleration(h, DragOverStep(drag, b), b.position, b.velocity, b.time, pressed);
  const double parting = k.normal.dot(b.velocity) + w.cross(k.normal).dot(b.position - o);
  // (Still approaching, parting < 0, the impulse left it: no hold, which would push it.)
  if (!(pressed > 0) || parting < 0 || parting * parting >= 2.0 * pressed * strike::kContactTolerance) return;
  held = h;
  b.velocity -= parting * k.normal;  // on the face (its kinetic energy at most m A delta)
  b.spin = Vec3::Zero();
  ++r.pushed_along;
}

// The next step of a held body's slide: RK4 of its motion on the face, put back on the face
// at the step's end (position and normal velocity), and the chord the searches follow
// (through both ends, as a free chord's).
NailFlight::Chord NailFlight::held_chord(double t_end) {
  const Held& h = *held;
  const strike::Spindle& sp = (*ctx.spindles)[h.spindle];
  const DragOverStep over(drag, b);
  const double dt = std::min(kHeldTurn / sp.omega(), t_end - b.time), t = b.time;
  double pressed = 0;
  const auto f = [&](const Vec3& c, const Vec3& v, double at) { return held_acceleration(h, over, c, v, at, pressed); };
  const Vec3 k1v = f(b.position, b.velocity, t), k1x = b.velocity;
  const Vec3 k2x = b.velocity + 0.5 * dt * k1v, k2v = f(b.position + 0.5 * dt * k1x, k2x, t + 0.5 * dt);
  const Vec3 k3x = b.velocity + 0.5 * dt * k2v, k3v = f(b.position + 0.5 * dt * k2x, k3x, t + 0.5 * dt);
  const Vec3 k4x = b.velocity + dt * k3v, k4v = f(b.position + dt * k3x, k4x, t + dt);
  Body next = b;
  next.time = t + dt;
  next.position = b.position + dt / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
  next.velocity = b.velocity + dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
  const Vec3 n = held_normal(h, next.time), w = spin_of(sp), o = axis_point(sp);
  next.position += (h.offset - n.dot(next.position - o)) * n;
  next.velocity -= (n.dot(next.velocity) + w.cross(n).dot(next.position - o)) * n;
  strike::Motion motion = chord_motion(b, k1v);
  if (dt > 0) motion.a = 2.0 * (next.position - b.position - b.velocity * dt) / (dt * dt);
  return {over, k1v, dt, next, next.position - b.position, (next.position - b.position).norm(), motion};
}

// A held step ended: logged, and let go when the push would pull, the real section no longer
// touches the body (past the face's edge, or beyond the arm's tip) or a quarter turn has gone.
void NailFlight::held_moved() {
  const Held& h = *held;
  const strike::Spindle& sp = (*ctx.spindles)[h.spindle];
  double pressed = 0;
  held_acceleration(h, DragOverStep(drag, b), b.position, b.velocity, b.time, pressed);
  const Vec3 n = held_normal(h, b.time);
  // The knife's contact goes on: what leaves it leaves at the held body's velocity.
  r.trace.last_strike_speed = b.velocity.norm();
  r.trace.last_strike_velocity = b.velocity;
  if (on_blade) r.launch_velocity = b.velocity;
  if (FlightEvent* e = log(FlightEvent::Kind::Push, b.position - nail.radius() * n, n)) {
    e->spindle = static_cast<std::uint16_t>(h.spindle), e->edge = static_cast<std::uint16_t>(h.edge), e->pressed = pressed;
  }
  const strike::Clearance gap = strike::clearance(sp, h.edge, phases.at_zero[h.spindle], nail, chord_motion(b, Vec3::Zero()), b.time);
  if (!(pressed > 0) || gap.off_arm || !(std::abs(gap.distance) <= kHeldSlack) || sp.omega() * (b.time - h.t0) > 0.5 * units::pi) {
    held.reset();
    last_contact = b.time, last_event = b.time;
  }
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

// The nail moved along the chord to where it touches a face; returns the touching point
// from its centre.
Vec3 NailFlight::meet(const FaceTouch& at, const Chord& chord) {
  return meet(as_touch(at), chord);
}

// The scene's face touched, as a surface met: its label and guard, the contact's point and
// normal (the face's, or an edge's or corner's, toward the nail).
scene::Hit NailFlight::face_hit(const FaceTouch& at) const {
  scene::Hit h;
  h.point = at.point, h.normal = at.normal, h.face = at.face;
  h.surface = ctx.scene->soup().labels[at.face];
  h.guard = ctx.scene->soup().guard_index[at.face];
  return h;
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
  const BoardStrike strike = board_strike(nail, at.axis, at.point - at.centre, n, velocity, b.spin, set.board.crush_depth);
  const double energy = strike.energy, width = strike.width;
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
    rebound(nail, b.axis, *arm, n, e, mu, b.velocity, b.spin, surface_inverse_mass, set.law);
  else if (surface_inverse_mass > 0 && b.velocity.dot(n) < 0)
    rebound(nail, b.axis, Vec3::Zero(), n, e, mu, b.velocity, b.spin, surface_inverse_mass, set.law);
  else
    b.velocity = bounce(b.velocity, n, e, mu);
}

bool NailFlight::respond(const scene::Hit& hit, const Vec3* arm) {
  const SurfaceMaterial& material = set.materials.of(hit.surface, hit.guard);
  const Vec3 n = hit.normal;
  const double speed_in = ctx.events ? b.velocity.norm() : 0.0;  // for a replay's trail only
  // The bounce is resolved in the frame of the surface (the turf moves under a field's mower).
  const Vec3 frame = surface_velocity(hit.surface, n);
  const bool moving = !frame.isZero(0.0);  // (shifted only then: adding a zero would turn -0.0 into 0.0)
  const double energy_in = ctx.events ? energy(frame) : 0.0;
  // How the surface meets the nail: its touching point's velocity over it (the centre's when it slides).
  const Vec3 v_in = (arm ? Vec3(b.velocity + b.spin.cross(*arm)) : b.velocity) - frame;
  const double approach = -v_in.dot(n);
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
        passing_guard = hit.guard;  // through its curtain: its faces are not met until the nail is clear of them
        if (FlightEvent* e = log(FlightEvent::Kind::GuardPass, hit.point, n, v_in.norm())) e->surface = hit.surface, e->face = hit.face, e->guard = hit.guard;
        return true;
      }
      break;  // else it bounces off the curtain
    case SurfaceMaterial::Response::Flap:
    case SurfaceMaterial::Response::Bounce: break;
  }
  if (ctx.observer && hit.surface == scene::Surface::Ground)
    ctx.observer->met_ground(b.time, arm ? Vec3(b.position + *arm) : hit.point, b.velocity, in_deck);
  // From here the nail's velocity is taken over the surface (restored below).
  if (moving) b.velocity -= frame;
  if (material.penetrability > 0 && arm && sinks_in(material, n, *arm)) {
    if (moving) b.velocity += frame;  // at rest in the soil, moving with it
    return false;
  }
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
  // A flap touched again at the instant it was struck (the object still pushing the flap it
  // set swinging) has given what its mass can: it is met as a rigid stop.
  const bool flap = material.response == SurfaceMaterial::Response::Flap;
  const bool pushing = flap && struck_flap == hit.guard && b.time - struck_flap_time <= 1e-9;
  const double give = flap && !pushing ? 1.0 / material.flap_mass_at(contact_height) : 0.0;
  if (flap) struck_flap = hit.guard, struck_flap_time = b.time;
  bounce_off(facet, material.restitution(std::max(-v_in.dot(n), 1e-9), angle), material.friction, arm, give);
  // A rough facet cannot send a point-like bounce into the surface. (A tumbling rod's centre
  // may still move into it after a rigid rebound at one end: its next touch is searched.)
  if (material.roughness > 0) {
    const double out = b.velocity.dot(n);
    if (out < 0 && !arm) b.velocity -= 2 * out * n;
  }
  if (skids_on(hit.surface)) b.spin = Vec3::Zero();  // (no energy is created by dropping it)
  if (moving) b.velocity += frame;
  bounced(hit, approach, arm ? Vec3(b.position + *arm) : hit.point, speed_in, energy_in, 1, frame);
  return true;
}

// What every bounce off the scene records, once the velocities are new: the surface touched,
// whether a guard turned it back, the count (a bounce or a gentle contact), the wedge watch,
// and the replay's event.
void NailFlight::bounced(const scene::Hit& hit, double approach, const Vec3& point, double speed_in, double energy_in, int together,
                         const Vec3& frame) {
  switch (hit.surface) {
    case scene::Surface::Housing: touch(Touch::Housing); break;
    case scene::Surface::Deflector: touch(Touch::Deflector); break;
    case scene::Surface::Guard: touch(Touch::GuardBounce); break;
    default: touch(Touch::Ground); break;
  }
  // Whether a nail that comes to rest under the mower was last turned back by a guard (a
  // bounce on the turf after it does not change that).
  if (hit.surface != scene::Surface::Ground) last_contact_guard = hit.surface == scene::Surface::Guard;
  // A contact approaching slower than a fall through the nail's own diameter is a gentle one:
  // one of the micro-impacts by which a sustained contact (sliding along an edge, under a
  // flap, on the turf) is followed. Each obeys the impact law; they are counted apart from
  // bounces, so that a long slide does not spend the bounce cap.
  const bool gentle = approach < gentle_speed;
  ++(gentle ? r.gentle_contacts : r.bounces);
  if (std::abs(hit.normal.z()) < kWallNormalZ) ++r.wall_contacts;
  if (together > 1) ++r.simultaneous_contacts;
  note_contact(b.time, hit.face);
  if (FlightEvent* e = log(FlightEvent::Kind::Bounce, point, hit.normal, speed_in))
    e->surface = hit.surface, e->face = hit.face, e->guard = hit.guard, e->energy_before = energy_in, e->energy_after = energy(frame),
    e->gentle = gentle, e->together = together;
}

// The touching points of one instant resolved together (docs/model.md §5.3, [contacts] model
// = "simultaneous"): Moreau's impact at several points. An impulse P_k at each point, with
// P_k.n_k >= 0; Newton's restitution at each (its normal velocity after at least -e_k times
// its approach, and no push beyond it where it is more) and Coulomb's cone (|P_t| <= mu P_n,
// opposing the slip), found by projected Gauss-Seidel over the points' accumulated impulses
// (as in Moreau and Jean's time stepping). Newton's law at several points can create energy:
// checked, the impulses are then found again with no restitution, and should that too, the
// points are left to the sequential law (returns false; also where any point is not a plain
// bounce: a curtain, a flap, the board).
bool NailFlight::respond_together(const FaceTouch& at) {
  struct Point {
    Vec3 r, n, P;
    double approach, e, mu, knn;
    Eigen::Matrix3d K;
    scene::Hit hit;
  };
  std::array<Point, FaceTouch::kMaxTouchPoints> pts;
  const int count = at.point_count;
  // Every point a plain bounce, on surfaces moving alike (in a field the turf moves and the
  // mower's faces do not): the points are then resolved in that surface's frame.
  const auto velocity_at = [&](const TouchPoint& tp) { return surface_velocity(ctx.scene->soup().labels[tp.face], tp.normal); };
  const Vec3 frame = velocity_at(at.points[0]);
  for (int k = 0; k < count; ++k) {
    const TouchPoint& tp = at.points[static_cast<std::size_t>(k)];
    if (set.materials.of(ctx.scene->soup().labels[tp.face], ctx.scene->soup().guard_index[tp.face]).response !=
        SurfaceMaterial::Response::Bounce)
      return false;
    // (Alike to round-off: the touching points' normals on one face differ in their last bits.)
    if ((velocity_at(tp) - frame).norm() > 1e-9 * set.materials.ground().velocity.norm()) return false;
  }
  const bool moving = !frame.isZero(0.0);
  if (moving) b.velocity -= frame;  // restored below, on every way out
  const Eigen::Matrix3d inv_i = strike::inverse_inertia(nail, b.axis);
  for (int k = 0; k < count; ++k) {
    const TouchPoint& tp = at.points[static_cast<std::size_t>(k)];
    Point& p = pts[static_cast<std::size_t>(k)];
    p.hit.point = tp.point, p.hit.normal = tp.normal, p.hit.face = tp.face;
    p.hit.surface = ctx.scene->soup().labels[tp.face];
    p.hit.guard = ctx.scene->soup().guard_index[tp.face];
    const SurfaceMaterial& material = set.materials.of(p.hit.surface, p.hit.guard);
    p.r = tp.arm, p.n = tp.normal, p.P = Vec3::Zero();
    const Vec3 u = b.velocity + b.spin.cross(p.r);
    p.approach = std::max(0.0, -u.dot(p.n));
    const double speed = u.norm();
    const double angle = material.by_angle && speed > 0 ? std::asin(std::clamp(p.approach / speed, 0.0, 1.0)) : 0.5 * units::pi;
    p.e = std::clamp(material.restitution(std::max(p.approach, 1e-9), angle), 0.0, 1.0);
    p.mu = material.friction;
    p.K = strike::nail_compliance(nail, inv_i, p.r);
    p.knn = p.n.dot(p.K * p.n);
  }
  const double energy_in = energy();
  const double scale = 1e-13 * mass * (b.velocity.norm() + b.spin.norm() * nail.half_segment() + 1e-9);
  const auto solve = [&](bool restitution, Vec3& v, Vec3& w) {
    v = b.velocity, w = b.spin;
    for (int k = 0; k < count; ++k) pts[static_cast<std::size_t>(k)].P = Vec3::Zero();
    const auto apply = [&](const Point& p, const Vec3& dP) {
      v += dP / mass;
      w += inv_i * p.r.cross(dP);
    };
    for (int sweep = 0; sweep < 500; ++sweep) {
      double change = 0;
      for (int k = 0; k < count; ++k) {
        Point& p = pts[static_cast<std::size_t>(k)];
        // Normal: to the target velocity, the accumulated impulse kept pushing (>= 0).
        const double target = restitution ? p.e * p.approach : 0.0;
        const double pn = p.P.dot(p.n);
        const double pn_new = std::max(0.0, pn + (target - (v + w.cross(p.r)).dot(p.n)) / p.knn);
        Vec3 dP = (pn_new - pn) * p.n;
        apply(p, dP);
        // Friction: toward stopping the slip, the accumulated tangential impulse in the cone.
        const Vec3 u = v + w.cross(p.r);
        const Vec3 ut = u - u.dot(p.n) * p.n;
        const Vec3 pt = p.P - pn * p.n;
        Vec3 pt_new = pt;
        if (ut.norm() > 0) {
          const Vec3 t = ut.normalized();
          pt_new = pt - (ut.norm() / t.dot(p.K * t)) * t;
        }
        const double cone = p.mu * pn_new;
        if (pt_new.norm() > cone) pt_new *= cone / pt_new.norm();
        apply(p, pt_new - pt);
        dP += pt_new - pt;
        p.P = pn_new * p.n + pt_new;
        change = std::max(change, dP.norm());
      }
      if (change <= scale) break;
    }
    w = nail.without_axial_spin(w, b.axis);  // (as after any contact)
  };
  const auto energy_of = [&](const Vec3& v, const Vec3& w) {
    return 0.5 * mass * v.squaredNorm() + 0.5 * nail.transverse_inertia() * w.squaredNorm() - mass * kGravity.z() * b.position.z();
  };
  Vec3 v, w;
  solve(true, v, w);
  if (!(energy_of(v, w) <= energy_in + 1e-12 * std::abs(energy_in))) solve(false, v, w);
  if (!(energy_of(v, w) <= energy_in + 1e-12 * std::abs(energy_in)) || !v.allFinite() || !w.allFinite()) {
    if (moving) b.velocity += frame;
    return false;
  }
  const double speed_in = ctx.events ? (b.velocity + frame).norm() : 0.0;
  double approach = 0;
  for (int k = 0; k < count; ++k) approach = std::max(approach, pts[static_cast<std::size_t>(k)].approach);
  b.velocity = moving ? Vec3(v + frame) : v, b.spin = w;
  for (int k = 0; k < count; ++k)
    if (skids_on(pts[static_cast<std::size_t>(k)].hit.surface)) b.spin = Vec3::Zero();  // (as in respond())
  bounced(pts[0].hit, approach, b.position + pts[0].r, speed_in, energy_in, count, frame);
  return true;
}

// The nail comes to lie on the ground face through `on` with upward normal `up`: a rod falls
// flat (its axis turned into the face, about its centre, which comes down: no energy is
// gained), a sphere sits on it; its lowest point kLyingGap above the face. Pushed sideways
// out of any wall the flat rod would reach into.
void NailFlight::lie_down(const Vec3& up, const Vec3& on) {
  Vec3 flat = b.axis - b.axis.dot(up) * up;
  if (!(flat.norm() > 1e-9)) flat = up.unitOrthogonal();
  b.axis = flat.normalized();
  // Down onto the face, never up: a nail already lying lower (within the touch tolerance, or
  // a field's stone pressed into the soil) stays as low as it is.
  b.position += std::min(0.0, nail.radius() + kLyingGap - up.dot(b.position - on)) * up;
  for (int pass = 0; pass < 4; ++pass) {
    gather_here();
    double worst = 0;
    Vec3 away = Vec3::Zero();
    for (std::size_t i = 0; i < candidate_count; ++i) {
      const auto st = segment_face(b.position - nail.half_segment() * b.axis, b.position + nail.half_segment() * b.axis, *ctx.scene, candidates[i]);
      const double overlap = nail.radius() + kLyingGap - st.distance;
      Vec3 out = st.on_segment - st.on_triangle;
      out -= out.dot(up) * up;  // sideways only
      if (overlap > worst && out.norm() > 1e-12) worst = overlap, away = out.normalized();
    }
    if (worst <= 0) break;
    b.position += (worst + kLyingGap) * away;
  }
}

bool NailFlight::sinks_in(const SurfaceMaterial& material, const Vec3& n, const Vec3& arm) {
  const double h = nail.half_segment();
  if (!(h > 0)) return false;  // a sphere (a field's stone) is blunt: it bounces
  // The point is the +axis end (the end the feed holds up: a falling nail's heavy head leads);
  // the head, blunt and about 2.7 times the shank's width, is taken not to sink in.
  if (arm.dot(b.axis) < h - 1e-9) return false;  // touching at the head or along the shank
  if (b.axis.dot(-n) < std::cos(0.25 * units::pi)) return false;  // more flat than point-first
  // Moving along its axis (Young's equation is for a penetrator without yaw): the point's
  // velocity within 30 deg of it.
  const Vec3 v_point = b.velocity + b.spin.cross(arm);
  const double speed = v_point.dot(b.axis);
  if (!(speed > 0) || speed < std::cos(units::pi / 6) * v_point.norm()) return false;
  const double depth = young_depth(material.penetrability, mass, nail.diameter, speed);
  if (depth < kSinksDeeper * nail.diameter) return false;
  const double before = ctx.events ? energy() : 0.0;
  b.velocity = Vec3::Zero(), b.spin = Vec3::Zero();
  ended_at_rest = true;
  touch(Touch::Ground);
  if (FlightEvent* e = log(FlightEvent::Kind::Rest, b.position + arm, n, speed)) e->energy_before = before, e->energy_after = energy();
  return true;
}

// On the ground after `hit` with too little rebound to fly: slides to rest, or into a wall
// and on. Returns false when the flight has ended (at rest, stopped, cut off).
bool NailFlight::slide(const scene::Hit& hit) {
  held.reset();  // on the ground now (a nudge's slide from where it lies): no knife holds it
  Vec3 up = ctx.scene->face_normal(hit.face);
  if (up.dot(hit.normal) < 0) up = -up;
  const double friction_decel = set.materials.of(hit.surface, hit.guard).friction * -kGravity.z() * std::max(0.0, up.z());
  // The turf's own velocity along its face (a field's, seen from the travelling mower; zero in
  // the J232 test): friction acts on the slip over it, and the still air's drag on the
  // object's speed through it, which on the ground are the same (both rest in the ground's frame).
  const Vec3& ground = set.materials.ground().velocity;
  const Vec3 turf = ground - ground.dot(up) * up;
  const double before = ctx.events ? energy() : 0.0;
  lie_down(up, hit.point);
  if (FlightEvent* e = log(FlightEvent::Kind::Slide, b.position, up, b.velocity.norm())) e->energy_before = before, e->energy_after = energy();
  bool stopped = false, escaped = false;
  bool against_mower = false;  // held against a face of the mower by the turf (below)
  // A face of the mower the moving turf presses the object into (in a field), while it slides
  // along it: the face's normal (zero: none). The face takes the push into it; the object
  // slides along the face, slowed by the face's friction too.
  Vec3 pressed = Vec3::Zero();
  double pressed_mu = 0;
  std::uint32_t pressed_face = 0;
  double ceiling_touched = -HUGE_VAL;  // when it last touched a face over it (below)
  // Pushed along by the mower, held at the face of normal `n` (friction `mu`) that the moving
  // turf presses it into: slowed to the mower's pace there, the turf's pull along the face
  // within the face's friction cone, |turf_t| <= mu |turf.n|.
  const auto held_at = [&](const Vec3& n, double mu) {
    const double into = -turf.dot(n), along = (turf + into * n).norm();
    return into > 1e-9 && along <= mu * into && (b.velocity - b.velocity.dot(up) * up).norm() <= set.rest_speed;
  };
  for (int part = 0; !stopped; ++part) {
    Vec3 slip = b.velocity - b.velocity.dot(up) * up - turf;
    const double speed = slip.norm();
    if (r.bounces > set.max_bounces || r.gentle_contacts > set.max_gentle_contacts || !std::isfinite(speed) || part > kMaxSlideParts ||
        b.time >= start.time + set.time_limit) {
      cut(!std::isfinite(speed)                        ? CutOff::NonFinite
          : b.time >= start.time + set.time_limit      ? CutOff::TimeLimit
          : r.bounces > set.max_bounces                ? CutOff::MaxBounces
          : part > kMaxSlideParts                      ? CutOff::FlightSteps
                                                       : CutOff::MaxGentleContacts);
      break;
    }
    // Slid or rolled out of the space followed (ctx.escape_radius: a field's, beyond its
    // tallied square's corners; a J232 test's, 1 m beyond the board ring), as a flight leaves
    // it (event_check): ended there. (A round stone rolling at 30 m/s on 0.12 g ran 350 m
    // before the time limit cut it off.)
    if (b.position.x() * b.position.x() + b.position.y() * b.position.y() > ctx.escape_radius * ctx.escape_radius) {
      escaped = true;
      break;
    }
    // Slowed to the mower's pace at the wall the turf presses it into, it is held there, as
    // when it meets the wall at that pace (below). (Else it had slid on at no speed, part after
    // part, until the time limit: a stone stopped against the rear chains.) Only while it
    // still touches that face: slid past its end, or off a convex skirt's facet along its
    // plane, it is free of it.
    if (pressed.squaredNorm() > 0 && face_clearance(*ctx.scene, pressed_face, nail, b.position, b.axis) > kPressedGap) pressed = Vec3::Zero();
    if (pressed.squaredNorm() > 0 && !against_mower) against_mower = held_at(pressed, pressed_mu);
    // At rest on the turf, or pushed along by the mower (below).
    if (speed < set.rest_speed || against_mower || (friction_decel <= 0 && !drag.on)) {
      b.velocity = Vec3::Zero();
      b.spin = Vec3::Zero();
      ended_at_rest = true;
      held_by_mower = against_mower;
      log(FlightEvent::Kind::Rest, b.position, up);
      break;
    }
    slip /= speed;
    // Air drag along the track at slip speed u (its component across the track and off the
    // ground is taken by friction and the ground): a fast skid's drag outweighs its friction
    // (a 50 mm stone at 60 m/s: about three times).
    const auto drag_along = [&](double u) { return drag.on ? std::max(0.0, -drag_acceleration(drag, Vec3(turf + u * slip), b.axis).dot(slip)) : 0.0; };
    // The lying capsule slides straight at constant deceleration over each part, until it
    // stops or touches a face (a wall, a skirt's foot, another ground face); the face it lies
    // on stays kLyingGap below. Where drag counts (above a hundredth of friction), a part ends
    // where the speed has fallen by a tenth, its deceleration friction plus the drag at its
    // middle speed (the stop's distance then within 0.1 % of the integral's); else one part
    // runs to the stop.
    double end_speed = 0;
    // A ball (rolling()) slips at the turf's friction until its contact point stops slipping,
    // then rolls, slowed by the ground's rolling resistance and by drag (of which its spin
    // takes 2/7: a rolling solid sphere's effective mass is 7/5 of its mass). Friction -mu g
    // u_hat at the contact (u its slip) slows the centre by mu g and spins it up by
    // (5/2) mu g / R about up x u_hat, so the slip closes at (7/2) mu g along u_hat.
    const double radius = nail.radius();
    Vec3 contact_slip = Vec3::Zero(), spin_rate = Vec3::Zero();
    bool rolling_now = false;
    if (rolling()) {
      contact_slip = b.velocity - turf + b.spin.cross(Vec3(-radius * up));
      contact_slip -= contact_slip.dot(up) * up;
      // Rolling on holds only while friction can keep the contact still: drag slows the centre
      // and not the spin, and friction must give the spin 2/7 of that deceleration, at most
      // mu g n_z (a small fast stone's drag breaks it: it slips, friction forward).
      rolling_now = contact_slip.norm() <= kRollingSlip && 2.0 / 7.0 * drag_along(speed) <= friction_decel;
      if (rolling_now) {  // rolling: the spin that rolls it, about a horizontal axis across the track
        b.spin = up.cross(Vec3(speed * slip)) / radius;
        b.axis = slip;  // (a sphere's axis is any: along the track, so that the roll is across it)
      }
    }
    const double resisting = rolling_now ? set.materials.ground().rolling_resistance * -kGravity.z() * std::max(0.0, up.z()) : friction_decel;
    const double drag_share = rolling_now ? 5.0 / 7.0 : 1.0;
    if (drag_along(speed) > 0.01 * resisting) end_speed = 0.9 * speed >= set.rest_speed ? 0.9 * speed : 0.0;
    const double drag_mid = drag_share * drag_along(0.5 * (speed + end_speed));
    Vec3 accel = -(resisting + drag_mid) * slip;
    double decel = resisting + drag_mid;
    double slip_ends = HUGE_VAL;  // a slipping ball: when its contact stops slipping
    if (rolling() && !rolling_now) {
      // (No slip yet but more drag than friction can hold: the contact starts to slip
      // backward, friction acting forward.)
      const Vec3 across = contact_slip.norm() > kRollingSlip ? Vec3(contact_slip.normalized()) : Vec3(-slip);
      accel = -friction_decel * across - drag_mid * slip;
      decel = -accel.dot(slip);
      spin_rate = 2.5 * friction_decel / radius * up.cross(across);
      const double closing = 3.5 * friction_decel + drag_mid * slip.dot(across);
      // (From no slip the part runs by the speed's rule: the slip has yet to open.)
      if (closing > 0 && contact_slip.norm() > kRollingSlip) slip_ends = contact_slip.norm() / closing;
    }
    if (!(decel > 0) && slip_ends == HUGE_VAL) {
      b.velocity = Vec3::Zero();
      b.spin = Vec3::Zero();
      ended_at_rest = true;
      log(FlightEvent::Kind::Rest, b.position, up);
      break;
    }
    strike::Motion m;
    m.p0 = b.position, m.v0 = turf + speed * slip, m.a = accel, m.t0 = b.time, m.axis0 = b.axis;
    double part_end = b.time + std::min(decel > 0 ? (speed - end_speed) / decel : HUGE_VAL, slip_ends);
    // Bounced off the wall faster than the rest speed: free of it. Slower, the rebound is none
    // (as a bounce slower than the rest speed is rest): held at the wall. (Kept pressed while
    // moving off it, it had kept that speed with nothing slowing it, the wall having taken the
    // deceleration back towards it: a cobble crossed the deck at 0.4 m/s for seconds.)
    if (pressed.squaredNorm() > 0 && m.v0.dot(pressed) > set.rest_speed) pressed = Vec3::Zero();
    if (pressed.squaredNorm() > 0) {
      // Against the wall: what would move it into or off the wall the wall takes (its velocity
      // and acceleration into it removed, and a rebound slower than the rest speed), its
      // friction slowing the motion along it; the part ends where that motion stops or the
      // speed has fallen as above.
      const double v_in = m.v0.dot(pressed), a_in = m.a.dot(pressed);
      m.v0 -= v_in * pressed;
      if (a_in < 0) {
        m.a -= a_in * pressed;
        const Vec3 along = m.v0 - m.v0.dot(pressed) * pressed;
        if (along.norm() > 1e-12) m.a -= pressed_mu * -a_in * along.normalized();
      }
      const Vec3 v_along = m.v0 - m.v0.dot(pressed) * pressed;
      const double v_t = v_along.norm(), a_t = v_t > 1e-12 ? -(m.a - m.a.dot(pressed) * pressed).dot(v_along / v_t) : 0.0;
      if (v_t > 1e-12 && a_t > 0) part_end = std::min(part_end, b.time + v_t / a_t);
      if (a_in >= 0) pressed = Vec3::Zero();  // the turf no longer presses it in: it leaves the wall
    }
    // A slide whose swept box holds more faces than the search keeps (a long slide past a
    // chain curtain, a mesh, the plate's fan) is searched a part at a time, as chords are:
    // the part's end is a point of the same motion, so the slide is unchanged by the split.
    double until = part_end;
    while (gather(m, b.time, until) > candidates.size()) {
      if (until - b.time <= 1e-9) {  // (as a chord's: too many faces even for a nanosecond's slide)
          cut(CutOff::SearchSteps);
        break;
      }
      until = b.time + 0.5 * (until - b.time);
    }
    if (cut_off) break;
    J232_CHECK(candidate_count <= candidates.size());
    FaceSearchStats stats;
    const auto wall = first_face_touch(*ctx.scene, candidates.data(), candidate_count, m, nail, b.time, until, filter(), stats);
    r.search_steps += stats.steps;
    if (stats.gave_up || stats.sank) {
      cut(stats.sank ? CutOff::SankIntoFace : CutOff::SearchSteps);
      break;
    }
    // The knives meet an object sliding under the deck as they meet one in flight (a stone
    // standing up into the blades' plane): the part is searched against them up to its end.
    std::optional<strike::Contact> knife;
    if (in_deck && ctx.spindles) {
      strike::Motion turning = m;
      turning.spin = b.spin;  // (a rolling ball's: the strike's impulse uses it)
      knife = blade_contact(turning, wall ? wall->time : until);
      if (cut_off) break;
    }
    const double t0 = b.time, t1 = knife ? knife->time : wall ? wall->time : until;
    const Vec3 from = b.position;
    stretch(m, t0, t1);
    b.spin += spin_rate * (t1 - t0);  // a slipping ball spun up by friction
    if (rolling_now) b.spin = up.cross(Vec3(m.velocity(t1) - turf)) / radius;
    if (knife) {
      if (ctx.observer) ctx.observer->flew(t0, from, m.velocity(t0), t1, knife->centre, m.velocity(t1));
      moved(from, knife->centre);
      b.position = knife->centre, b.velocity = m.velocity(t1), b.axis = knife->axis, b.time = t1;
      last_event = b.time;
      restrike(*knife);
      return !cut_off;
    }
    if (!wall) {
      const Vec3 to = m.centre(until);
      if (ctx.observer) ctx.observer->flew(t0, from, m.velocity(t0), until, to, m.velocity(until));
      moved(from, to);
      b.position = to, b.time = until, b.velocity = m.velocity(until);
      last_event = b.time;
      if (until < part_end || end_speed > 0 || slip_ends < HUGE_VAL) continue;  // the slide goes on from the part's end
      b.velocity = Vec3::Zero();
      b.spin = Vec3::Zero();
      ended_at_rest = true;
      log(FlightEvent::Kind::Rest, b.position, up);
      break;
    }
    b.time = wall->time, b.position = wall->centre, b.velocity = m.velocity(wall->time);
    last_event = b.time;
    if (ctx.observer) ctx.observer->flew(t0, from, m.velocity(t0), b.time, b.position, b.velocity);
    moved(from, b.position);
    const scene::Hit met = face_hit(*wall);
    stopped = !respond(met);
    if (cut_off) break;
    if (set.materials.of(met.surface, met.guard).holds_up) break;  // slid onto another ground face: fly on from there
    // Touching a face over it (a skirt's lower edge, the deck's underside) again at the same
    // instant: its track closes the gap between that face and the ground. It goes on along
    // the crease between the two (the velocity across it taken by both faces: along a
    // skirt's lip, past a seam of its facets), or, left slower than the rest speed, it is
    // jammed there: at rest, held by the mower where the moving turf presses it into the face
    // within the face's friction, else left to the turf. (Else it touched the face again and
    // again at no progress, a hundredth of a m/s lost each time, until the step cap: a
    // 38.1 mm stone under a 1.5-in skirt.)
    if (last_touch != Touch::GuardPass && met.normal.dot(up) < -kCeilingSlope) {
      if (b.time - ceiling_touched <= kWedgeGap) {
        const Vec3 crease = up.cross(met.normal);
        const Vec3 along = crease.norm() > 1e-9 ? Vec3(crease.normalized()) : Vec3::Zero();
        b.velocity = b.velocity.dot(along) * along;
        if (b.velocity.norm() <= set.rest_speed) {
          const Vec3 across = met.normal - met.normal.dot(up) * up;
          held_by_mower = across.norm() > 1e-9 && held_at(across.normalized(), set.materials.of(met.surface, met.guard).friction);
          b.velocity = Vec3::Zero();
          b.spin = Vec3::Zero();
          ended_at_rest = true;
          log(FlightEvent::Kind::Rest, b.position, up);
          break;
        }
      }
      ceiling_touched = b.time;
    }
    // Pressed into the mower's face by the turf moving under it (in a field) and slowed there
    // to the mower's pace, it is pushed along by the mower (at rest in the mower's frame, held
    // there) when the face's friction holds it. Not after passing through a curtain.
    const double into = -turf.dot(met.normal), mu = set.materials.of(met.surface, met.guard).friction;
    against_mower = last_touch != Touch::GuardPass && held_at(met.normal, mu);
    // Else, pressed into it, it slides along it (the next parts); through a curtain, on.
    pressed = Vec3::Zero();
    if (last_touch != Touch::GuardPass && into > 1e-9) {
      pressed = met.normal - met.normal.dot(up) * up;
      pressed = pressed.norm() > 1e-9 ? Vec3(pressed.normalized()) : Vec3::Zero();
      pressed_mu = mu;
      pressed_face = met.face;
    }
  }
  return !(stopped || escaped || ended_at_rest || cut_off);
}

// After a bounce off `hit`: on the ground with too little rebound to fly, it slides to rest
// or into a wall and on; at rest only on something that holds it up (not under the deck
// plate, not on a wall) and only where friction can hold it (the face no steeper than the
// friction angle). Returns false when the flight has ended.
bool NailFlight::after_bounce(const scene::Hit& hit) {
  // How fast its ends swing about its centre: a nail still tumbling is not lying yet.
  const double swing = b.spin.norm() * nail.half_segment();
  const SurfaceMaterial& material = set.materials.of(hit.surface, hit.guard);
  Vec3 up = ctx.scene->face_normal(hit.face);
  if (up.dot(hit.normal) < 0) up = -up;
  if (material.holds_up && up.z() > 0 && b.velocity.dot(up) < kSlideBelow && swing < kSlideBelow) {
    // Lying on the ground, it slides without turning; a ball that rolls keeps the spin about
    // the ground's plane it has (its contact's slip decides how it goes on).
    b.spin = rolling() ? Vec3(b.spin - b.spin.dot(up) * up) : Vec3::Zero();
    if (!slide(hit)) return false;
  }
  const bool within_friction_cone = up.z() * std::sqrt(1 + material.friction * material.friction) >= 1;
  // (At rest over the surface: a field's turf moves under the mower.)
  if ((b.velocity - surface_velocity(hit.surface, up)).norm() < set.rest_speed && swing < set.rest_speed && up.z() > 0.5 &&
      within_friction_cone) {
    ended_at_rest = true;
    log(FlightEvent::Kind::Rest, b.position, up);
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
  if (cut_off) return false;  // (a limit met within the last event: a wedge)
  if (!b.position.allFinite() || !b.velocity.allFinite() || !std::isfinite(b.time)) {
    r.non_finite = true;
    cut(CutOff::NonFinite);
    return false;
  }
  if (b.time >= t_end || r.bounces > set.max_bounces || r.gentle_contacts > set.max_gentle_contacts || ++steps > kMaxFlightSteps ||
      r.strikes > set.max_strikes) {
    cut(b.time >= t_end                              ? CutOff::TimeLimit
        : r.bounces > set.max_bounces                 ? CutOff::MaxBounces
        : r.gentle_contacts > set.max_gentle_contacts ? CutOff::MaxGentleContacts
        : steps > kMaxFlightSteps                     ? CutOff::FlightSteps
                                                      : CutOff::MaxStrikes);
    return false;
  }
  const double horizontal2 = b.position.x() * b.position.x() + b.position.y() * b.position.y();
  return !(horizontal2 > ctx.escape_radius * ctx.escape_radius || b.position.z() < -1.0);
}

// The chord of free flight from `from` over dt: where the drag integration ends it, and the
// motion the contact searches follow along it (its centre's parabola runs through both ends
// of the chord, so that the end the nail is placed at is the one the search proved clear).
NailFlight::Chord NailFlight::chord_from(const Body& from, double dt, const DragOverStep& over, const Vec3& accel) const {
  Body next = advance(from, dt, over, accel);
  strike::Motion motion = chord_motion(from, accel);
  if (dt > 0) motion.a = 2.0 * (next.position - from.position - from.velocity * dt) / (dt * dt);
  next.axis = motion.axis(from.time + dt);
  return {over, accel, dt, next, next.position - from.position, (next.position - from.position).norm(), motion};
}

// The faces the capsule may meet over [from, until] moving as `m` (the broad phase), into
// `candidates`; returns how many there are (more than kMaxCandidates: too many to keep).
std::size_t NailFlight::gather(const strike::Motion& m, double from, double until, bool counted) {
  Vec3 lo, hi;
  swept_box(m, nail, from, until, lo, hi);
  r.queries += counted;
  const std::size_t found = ctx.scene->faces_in_box(lo, hi, candidates.data(), candidates.size());
  candidate_count = std::min(found, candidates.size());
  return found;
}

// What the search passes over: the curtain the nail is going through, until it is clear
// of every one of its faces.
FaceFilter NailFlight::filter() {
  FaceFilter f{ctx.scene, passing_guard};
  if (in_field()) f.start_depths = &start_depths;
  if (passing_guard >= 0) {
    bool clear = true;
    for (std::size_t i = 0; i < candidate_count && clear; ++i)
      if (f.ignores(candidates[i]) && face_clearance(*ctx.scene, candidates[i], nail, b.position, b.axis) <= kFaceTolerance) clear = false;
    if (clear) passing_guard = -1, f.ignored_guard = -1;
  }
  return f;
}

// The next chord of free flight from where the nail is: the drag and acceleration shared by
// the chord's length, its step and a step to a touch on it; where it would end; the motion
// the contact searches follow along it; and the faces it may meet (a chord that sweeps more
// faces than the search keeps is halved).
NailFlight::Chord NailFlight::event_advance(double t_end) {
  if (held) {
    Chord c = held_chord(t_end);
    if (gather(c.motion, b.time, b.time + c.dt) <= candidates.size()) return c;
    held.reset();  // too many faces about it for one step: let go, and step freely
  }
  const DragOverStep step_drag(drag, b);
  const Vec3 accel = step_drag.acceleration(b.velocity, b.axis);
  double dt = std::min(chord_step(b, accel, set.chord_tolerance, kMaxChord, step_drag), t_end - b.time);
  for (;;) {
    Chord c = chord_from(b, dt, step_drag, accel);
    if (gather(c.motion, b.time, b.time + dt) <= candidates.size()) return c;
    // Even a nanosecond's chord sweeps more faces than the search keeps: a body as large as
    // the scene's detail (a 300 mm rod among chain links). Searching only some of them would
    // not be conservative, and halving on would take millions of chords: cut off, counted.
    if (dt < 1e-9) {
      cut(CutOff::SearchSteps);
      return c;
    }
    dt *= 0.5;
  }
}

// What ends the chord first: a face of the scene the capsule touches (any part of it, found
// conservatively: flight/face_touch.hpp), the blades (searched only up to that touch), or
// nothing.
NailFlight::NextEvent NailFlight::event_find(const Chord& c) {
  NextEvent e;
  // Just struck: the knife, driven round, is back on its path at once (its recoil is not
  // kept), so a heavy object still approaching it is caught again at this same instant, each
  // impulse smaller, until it moves with the knife's point there (a cobble: about 14
  // impulses). A touch at this instant is the earliest event whatever the faces do, and the
  // blade search over this instant alone finds exactly the touch the whole chord's would (the
  // same probes at this instant; a knife not touching here is found by neither): the face
  // search is not needed for it. (The reference search, which bisects back from its first
  // probe, is left to the whole chord.)
  if (std::exchange(struck_now, false) && fast_blade_search) {
    e.contact = blade_contact(c.motion, b.time);
    if (cut_off) return e;
    if (e.contact) {
      e.kind = NextEvent::Kind::Blade;
      return e;
    }
  }
  const double chord_end = b.time + c.dt;
  FaceSearchStats stats;
  e.touch = first_face_touch(*ctx.scene, candidates.data(), candidate_count, c.motion, nail, b.time, chord_end, filter(), stats);
  r.search_steps += stats.steps;
  if (stats.gave_up) cut(CutOff::SearchSteps);
  if (stats.sank) cut(CutOff::SankIntoFace);
  e.contact = blade_contact(c.motion, e.touch ? e.touch->time : chord_end);
  if (cut_off) return e;
  e.kind = e.contact ? NextEvent::Kind::Blade : e.touch ? NextEvent::Kind::Surface : NextEvent::Kind::ChordEnd;
  return e;
}

// What the event does to the nail. Returns false when the flight has ended.
bool NailFlight::event_collide(const Chord& c, const NextEvent& e) {
  stretch(c.motion, b.time,
          e.kind == NextEvent::Kind::ChordEnd ? b.time + c.dt : e.kind == NextEvent::Kind::Blade ? e.contact->time : e.touch->time);
  switch (e.kind) {
    case NextEvent::Kind::ChordEnd:
      moved(b.position, c.next.position);
      b = c.next;
      if (held) held_moved();
      return true;
    case NextEvent::Kind::Blade: {
      held.reset();  // another knife meets it: let go, and struck
      const Vec3 from = b.position;
      b.position = e.contact->centre;
      b.velocity = c.motion.velocity(e.contact->time);
      b.axis = e.contact->axis;
      b.time = e.contact->time;
      moved(from, b.position);
      restrike(*e.contact);
      struck_now = true;
      return !cut_off;
    }
    case NextEvent::Kind::Surface: break;
  }
  held.reset();  // it meets a face of the scene: let go there
  const FaceTouch& at = *e.touch;
  const scene::Hit hit = face_hit(at);
  touched_scene();
  const Vec3 velocity = c.motion.velocity(at.time);
  const Vec3 arm = meet(at, c);
  if (set.materials.of(hit.surface, hit.guard).response == SurfaceMaterial::Response::Board) {
    reach_board(hit, as_touch(at), velocity);
    return false;
  }
  // Contacts at one instant resolved together ([contacts] model = "simultaneous"), where
  // they can be (plain bounces at every point); else one after the other.
  if (set.contacts == scenario::ContactModel::Simultaneous && at.point_count > 1 && respond_together(at)) return after_bounce(hit);
  if (!respond(hit, &arm)) return false;
  return after_bounce(hit);
}

// At rest on turf that moves under the mower (a field): carried with it toward the deck's
// rear, until a blade reaches it (struck again: the flight goes on) or it has crossed the
// deck (it stays where it lies). Returns true when struck again.
bool NailFlight::carried() {
  const Vec3& turf = set.materials.ground().velocity;
  const double speed = turf.norm();
  for (;;) {
    if (!(speed > 0) || !in_deck || !ctx.spindles || held_by_mower) return false;
    strike::Motion m;
    m.p0 = b.position, m.v0 = turf, m.a = Vec3::Zero(), m.t0 = b.time, m.axis0 = b.axis, m.spin = Vec3::Zero();
    // Long enough to cross the whole deck (and no longer than the flight may last).
    const double until = std::min(b.time + 2 * ctx.deck_radius / speed, start.time + set.time_limit);
    const auto k = blade_contact(m, until);
    if (!k || cut_off) return false;
    const Vec3 from = b.position;
    b.position = k->centre, b.velocity = turf, b.spin = Vec3::Zero(), b.axis = k->axis, b.time = k->time;
    moved(from, b.position);
    ended_at_rest = false;
    restrike(*k);
    if (cut_off) return false;
    // Nudged where it lay (a knife's edge grazing it, leaving it slower over the turf than a
    // gentle contact and not lifted): the soil it lies on or in holds it up, so it slides on
    // from where it is, as it would after the gentle touch it would otherwise fly to. (Left to
    // fly, it fell into the soil under gravity until that touch was found, a few micrometres
    // deeper at each graze.) A strike that sets it moving faster flies on, where the knives can
    // meet it again.
    if ((b.velocity - turf).norm() >= gentle_speed) return true;
    const std::optional<scene::Hit> bed = lying_on_ground();
    if (!bed || (b.velocity - surface_velocity(scene::Surface::Ground, bed->normal)).dot(bed->normal) > 0) return true;
    if (slide(*bed)) return true;
    if (!ended_at_rest || cut_off) return false;
    // At rest again. Come to rest at the instant it was nudged, the knife could not move it
    // (the soil holds it): the knife rides over it, as over a stone pressed into the soil,
    // rather than meeting it again at that instant for ever.
    if (b.time == k->time) ride_over(k->spindle, k->time);
  }
}

// The ground face the nail lies on or in now (its clearance within the lying gap, or below),
// the deepest if several: a hit on it, its normal up out of it.
std::optional<scene::Hit> NailFlight::lying_on_ground() {
  gather_here();
  std::optional<scene::Hit> bed;
  double deepest = kLyingGap + kFaceTolerance;
  const Vec3 p0 = b.position - nail.half_segment() * b.axis, p1 = b.position + nail.half_segment() * b.axis;
  for (std::size_t i = 0; i < candidate_count; ++i) {
    const std::uint32_t f = candidates[i];
    if (ctx.scene->soup().labels[f] != scene::Surface::Ground) continue;
    const SegmentTriangle st = segment_face(p0, p1, *ctx.scene, f);
    const double clearance = st.distance - nail.radius();
    if (!(clearance <= deepest)) continue;
    deepest = clearance;
    Vec3 up = ctx.scene->face_normal(f);
    if (up.dot(b.position - st.on_triangle) < 0) up = -up;
    bed = scene::Hit{};
    bed->point = st.on_triangle, bed->normal = up, bed->face = f, bed->surface = scene::Surface::Ground, bed->guard = 0;
  }
  return bed;
}

// The free stretch from where the nail is to the event that ends the chord, told to the
// context's observer.
void NailFlight::observe(const Chord& c, const NextEvent& e) const {
  double t1 = c.next.time;
  Vec3 p1 = c.next.position, v1 = c.next.velocity;
  switch (e.kind) {
    case NextEvent::Kind::ChordEnd: break;
    case NextEvent::Kind::Blade: t1 = e.contact->time, p1 = e.contact->centre, v1 = c.motion.velocity(t1); break;
    case NextEvent::Kind::Surface: t1 = e.touch->time, p1 = e.touch->centre, v1 = c.motion.velocity(t1); break;
  }
  ctx.observer->flew(b.time, b.position, b.velocity, t1, p1, v1);
}

// The flight as a loop of named events (as OpenMC's event_advance / event_collide): check
// that it goes on, plan the next chord, find what ends it, and let that act on the nail.
FlightResult NailFlight::run() {
  r.trace.last_strike_speed = start.velocity.norm();
  r.trace.last_strike_velocity = start.velocity;
  r.launch_velocity = start.velocity;
  const double t_end = start.time + set.time_limit;
  int steps = 0;
  if (ctx.path) ctx.path->push_back(b.position);
  if (in_field()) {
    // A field's object lies where it was placed, maybe pressed into the soil, under a curtain
    // draped over it or under the skirt riding over it: how deep, face by face (by the search's
    // own distances; the audit measures the same against the whole soup, independently).
    gather_here();
    const auto& labels = ctx.scene->soup().labels;
    for (std::size_t i = 0; i < candidate_count; ++i)
      if (const double g = face_clearance(*ctx.scene, candidates[i], nail, b.position, b.axis); g < 0)
        start_depths.add(candidates[i], -g, labels[candidates[i]] == scene::Surface::Ground);
  }
  while (event_check(t_end, steps)) {
    const Chord c = event_advance(t_end);
    if (cut_off) break;
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
