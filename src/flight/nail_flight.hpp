#pragma once
// One thrown nail from the blade to its end: chords against the scene, and what each
// surface does to it (docs/model.md §5.3; each surface's row of flight/surface_material.hpp):
//   target (operator zone or outside): the board model marks it (hit / puncture) or not;
//       either way the board catches the nail (it drops at the board's foot);
//   housing, deflector: bounce with restitution e(v) and Coulomb friction;
//   guard (chain or belting): passes between the links with probability `openness`,
//       keeping `pass_speed_factor` of its speed, or bounces;
//   blade (a spindle's turning plate): struck again wherever the capsule touches it, by
//       the same contact search and impulse as the feed's strike (strike/);
//   ground: bounce with restitution, friction and a random tilt of the local normal
//       (roughness); once the rebound is too weak to leave the ground (< 0.5 m/s) it
//       slides to rest under friction, still able to strike a wall on the way.
// The nail ends at the board, at rest, after max_bounces or time_limit, or leaving the scene.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "projectile/projectile.hpp"
#include "strike/contact_search.hpp"
#include "strike/spindle.hpp"
#include "flight/deck_outline.hpp"
#include "flight/flight_settings.hpp"
#include "flight/trajectory.hpp"
#include "random/stream.hpp"
#include "scenario/scenario.hpp"
#include "scene/operator_zone.hpp"
#include "scene/scene.hpp"

namespace j232::flight {

// Where a nail went: not struck by the blade; at rest under the mower (contained by the
// housing, or last turned back by a guard); caught by the board without a mark; marked
// the board where J232 counts it; marked it only below the counted height (J232 does not
// count marks below the blade plane); gone over (or past) the board; at rest outside the
// mower short of the board; or cut off still moving by the run's limits (time, bounces,
// steps) or a non-finite state. A cut-off nail's end is unknown, so too many of them make
// a run invalid.
enum class Fate : std::uint8_t {
  NotStruck,
  Contained,
  StoppedByGuard,
  ReachedBoardUnmarked,
  MarkedBoard,
  MarkedBelowCountedHeight,
  OverBoard,
  ShortOfBoard,
  CutOff
};
inline constexpr int kFates = 9;
// Which limit cut a nail off (a run whose cut-off share nears its invalidity limit names
// them, so the user knows which setting to raise).
enum class CutOff : std::uint8_t {
  None,
  TimeLimit,         // [run] time_limit
  MaxBounces,        // [run] max_bounces
  FlightSteps,       // kMaxFlightSteps chords
  MaxStrikes,        // [run] max_strikes blade strikes
  SearchSteps,       // strike::kMaxSearchSteps steps of one contact search
  ContactsInPass,    // [run] max_contacts_per_pass contacts in one pass
  UnresolvedContact, // a blade touch the impulse could not resolve
  NonFinite,         // a non-finite state
  MaxGentleContacts, // [run] max_gentle_contacts
  Wedged,            // contacts ever closer in time without end: pinched between a blade and a fixed face, or wedged
  SankIntoFace       // pressed deeper than flight::kDeepestSink into a face being left (a contact the search cannot follow)
};
inline constexpr int kCutOffReasons = 12;
const char* cut_off_name(CutOff c);  // "time_limit", "max_bounces", ...
// The scenario setting that raises the limit ("run.max_bounces"), or what the limit is when
// no setting raises it ("the flight's step cap").
const char* cut_off_setting(CutOff c);
// Chords per flight before the nail is cut off: a nail at rest takes a few hundred at most.
inline constexpr int kMaxFlightSteps = 200000;
const char* fate_name(Fate f);

// A wall, to the benchmark's count of events: a face whose normal is within 5.7 deg of level
// (|n_z| below this: the skirt's sides and panels, where a nail rides round the deck).
inline constexpr double kWallNormalZ = 0.1;

struct MarkRecord {
  Vec3 point = Vec3::Zero();
  double normal_energy = 0;  // J
  bool in_zone = false;
  bool puncture = false;
  bool counted = true;  // at or above the counted height (SAE J232: the blade plane)
};

// What a thrown nail touched after its first strike, in order, and how it left the deck
// (docs/model.md §5.3a): the trail that explains a mark.
enum class Touch : std::uint8_t { Blade, Housing, Deflector, GuardBounce, GuardPass, Ground, Board };
inline constexpr int kTouchKinds = 7;
const char* touch_name(Touch t);  // "blade", "housing", "deflector", "guard", "guard-pass", "ground", "board"

// Where the nail crossed the deck's outline going out: under the skirt, through a
// discharge opening, through a guard's curtain, over the deck; the deck's edge of a mesh
// deck (its openings are not named); or it never left (or came back in and stayed).
enum class Exit : std::uint8_t { Inside, UnderSkirt, Opening, Guard, OverDeck, DeckEdge };

struct NailTrace {
  static constexpr int kMaxTouches = 24;  // further touches are counted, not listed
  std::array<Touch, kMaxTouches> touches{};
  int touch_count = 0;
  // The way out: the last crossing of the outline going out, after which the nail stayed out
  // (reached the board, came to rest outside, left the test); a nail a guard turned back
  // in after it first crossed is not named as leaving there.
  Exit exit = Exit::Inside;
  std::uint16_t exit_index = 0;  // the opening (housing.openings) or guard (the scene's guard index)
  double exit_azimuth = 0;       // rad, about the origin, where it crossed the outline
  double exit_height = 0;        // m above ground there
  Exit first_exit = Exit::Inside;  // the first crossing going out, whether or not it stayed out
  std::uint16_t first_exit_index = 0;
  double last_strike_speed = 0;  // m/s off the last blade strike
  Vec3 last_strike_velocity = Vec3::Zero();  // its velocity then (the flight's frame)

  void touch(Touch t) {
    if (touch_count < kMaxTouches) touches[static_cast<std::size_t>(touch_count)] = t;
    ++touch_count;
  }
};

struct FlightResult {
  Fate fate = Fate::OverBoard;
  static constexpr int kMaxMarks = 4;  // marks beyond this are counted but not located
  std::array<MarkRecord, kMaxMarks> marks{};
  int mark_count = 0;  // every mark, counted or not
  // Counted marks only (at or above the counted height), by category; and the others.
  int hits_zone = 0, punctures_zone = 0, hits_outside = 0, punctures_outside = 0;
  int uncounted_marks = 0;
  // The first arrival at the board, marked or not: kinetic energy along the board's
  // normal and that energy per presented width (what the board model compares).
  double board_energy = -1;            // J; < 0: never reached the board
  double board_energy_per_width = -1;  // J/m
  int bounces = 0;          // contacts with the scene approaching at sqrt(2 g D) or faster
  int gentle_contacts = 0;  // slower: the micro-impacts of a sustained contact (docs/model.md §5.3)
  int simultaneous_contacts = 0;  // bounces of several points resolved together ([contacts] model = "simultaneous")
  int wall_contacts = 0;  // bounces and gentle contacts on a wall (kWallNormalZ): for the benchmark
  int strikes = 1;                        // blade contacts, the first (the feed's) included
  // Passes: an edge's contacts with the nail until they part (docs/model.md §5.1b). A pass
  // with more than [run] max_contacts_per_pass contacts cuts the nail off (counted, never silent).
  int passes = 1;
  int most_contacts_in_pass = 1;
  std::array<std::uint16_t, 32> passes_by_contacts{};  // [k]: passes of k + 1 contacts (the last: 32 or more)
  Vec3 launch_velocity = Vec3::Zero();  // as the nail leaves the blade (its last contact before it touches anything else)
  int search_steps = 0;                 // contact-search steps (for the benchmark)
  bool non_finite = false;                // the state stopped being a finite number (a bug or absurd input)
  CutOff cut_off = CutOff::None;          // what cut it off (fate CutOff), the first limit reached
  int queries = 0;                        // scene ray queries (for the benchmark)
  // A field's objects (whose ground takes strikes: flight::SurfaceMaterial::takes_strikes): strikes after which a knife
  // rode over the object pressed into the soil, and pushes along a knife (held on its face, or
  // contact by contact passes of more than 64 contacts).
  int ridden_over = 0, pushed_along = 0;
  double flight_time = 0;
  Vec3 end_position = Vec3::Zero();
  NailTrace trace;
};

// One event of a nail's flight, for replaying a nail (`j232 trace`): what happened, when
// and where, and the nail's state just after it. Recorded only when the context asks.
struct FlightEvent {
  // Push: a sphere held on a knife's face ([contacts] blade_push = "held"), logged at each step of its slide.
  enum class Kind : std::uint8_t { Strike, Bounce, GuardPass, Slide, Rest, Board, LeftDeck, End, Push };
  Kind kind = Kind::End;
  double time = 0;  // s on the blades' clock
  Vec3 centre = Vec3::Zero(), velocity = Vec3::Zero(), spin = Vec3::Zero(), axis = Vec3::UnitZ();  // after it
  Vec3 point = Vec3::Zero();   // the contact (Strike, Bounce, Board), or where it crossed the deck's outline
  Vec3 normal = Vec3::Zero();  // the surface's or the blade's at the contact, unit (zero when none)
  double speed_in = 0;         // m/s of the centre before it
  scene::Surface surface = scene::Surface::Ground;
  std::uint32_t face = 0;
  std::uint16_t guard = 0;
  std::uint16_t spindle = 0, edge = 0;  // Strike, Push
  double energy = 0, width = 0;         // Board: what the board model judged
  double pressed = 0;                   // Push: the face's push on the body per unit of its mass, m/s^2
  // Bounce, Slide: the nail's mechanical energy (kinetic, translational and rotational, and
  // potential) just before and just after (a bounce or the fall flat must not create any).
  double energy_before = 0, energy_after = 0;
  bool gentle = false;                  // Bounce: a gentle contact (approaching slower than sqrt(2 g D))
  int together = 1;                     // Bounce: points resolved together ([contacts] model = "simultaneous")
  int mark = 0;                         // Board: 0 none, 1 hit, 2 puncture
  Fate fate = Fate::OverBoard;          // End
};
const char* event_name(FlightEvent::Kind k);  // "strike", "bounce", "guard-pass", "slide", "rest", "board", "left-deck", "end", "push"

// One stretch of a flight between events: the capsule moved as `motion` over [from, until]
// (free flight along a chord, or sliding on the ground). Recorded for the audit of a replay
// (`j232 trace --check`): every stretch, end to end, is the capsule's whole path.
struct FlightStretch {
  strike::Motion motion;
  double from = 0, until = 0;
};

// Watches a flight as it goes (j232 hazard tallies where thrown objects cross planes and
// land around the mower); null in a J232 run. Times are on the blades' clock.
class FlightObserver {
 public:
  virtual ~FlightObserver() = default;
  // The centre flew freely from p0 (at t0, velocity v0) to p1 (at t1, arriving with v1):
  // every stretch of free flight, in order, up to the event that ends it.
  virtual void flew(double t0, const Vec3& p0, const Vec3& v0, double t1, const Vec3& p1, const Vec3& v1) = 0;
  // It met the ground at `point` arriving with `velocity` (before the bounce); `in_deck`:
  // under the mower's deck (inside its outline).
  virtual void met_ground(double t, const Vec3& point, const Vec3& velocity, bool in_deck) = 0;
};

// What the flight needs beyond the body: the scene, its settings (limits, board, the
// surfaces' materials), and the deck.
struct FlightContext {
  const scene::Scene* scene = nullptr;
  const FlightSettings* settings = nullptr;
  double escape_radius = 0;  // horizontal distance at which the nail has left the test
  double deck_radius = 0;
  double counted_height = 0;                               // marks below it are not counted (Scenario::counted_height)
  double board_near = HUGE_VAL;  // horizontal distance of the board's nearest point: a nail at rest short of it did not pass it
  const std::vector<strike::Spindle>* spindles = nullptr;  // the turning blades; none: nothing strikes again
  // The deck's outline in plan and what crossing it means: a generated deck names its
  // openings, skirt and plate heights; a mesh deck does not.
  const DeckOutline* deck_outline = nullptr;
  bool generated_deck = true;
  // A zone derived from a seated operator: whether a mark is in it is judged along the line
  // from the blade that threw the nail (null: the board's labels say).
  const scene::OperatorZone* zone = nullptr;
  double skirt_bottom = 0, deck_top = 0;
  // When set, the nail's centre is appended at the start and after every move (tracing
  // chosen nails again for pictures; the per-nail path of a run leaves it null).
  std::vector<Vec3>* path = nullptr;
  // When set, every event of the flight is appended (replaying one nail; null in a run).
  std::vector<FlightEvent>* events = nullptr;
  // When set, every stretch of its motion is appended (auditing a replay; null in a run).
  std::vector<FlightStretch>* stretches = nullptr;
  FlightObserver* observer = nullptr;  // when set, told of every free stretch and ground contact
  // A sphere that rolls on the ground (a field's ball or round stone) rather than skids.
  bool rolls = false;
};

// A knife that rode over a field's object pressed into the soil touches it no more for this
// much of its turn (docs/model.md §9.1; docs/validation.md §5 shows what halving it does).
inline constexpr double kRideOverTurn = 0.5 * 3.14159265358979323846;

// The blade contact the flight starts from (the feed's strike): its pass goes on.
struct FirstContact {
  std::size_t spindle = 0, edge = 0;
  // Its knife rode over the object (pressed into the soil): no touch of that spindle before this time.
  double ridden_until = -HUGE_VAL;
};

// `drag` already scaled to this nail's mass; `phases`: the blades' angles at time 0 of the
// nail's clock (start.time is on it).
FlightResult fly(const Body& start, const projectile::Projectile& nail, const Drag& drag, const FlightContext& context,
                 const strike::BladePhases& phases, const FirstContact& first, random::EventDraws& draws);

}  // namespace j232::flight
