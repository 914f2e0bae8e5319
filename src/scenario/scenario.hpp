#pragma once
// A J232 assessment scenario: everything one simulated test needs, typed, checked
// and in SI. Plain data: it does not know the file format (scenario/scenario_reader.hpp
// reads a TOML file into it) (docs/model.md §5). Defaults are sourced values (docs/model.md §8) or report
// 445-1's; docs/model.md lists them
// with their sources, and every result echoes the values used.
//
// World frame: origin on the spindle axis at ground level, z up, x forward (the
// direction of travel), y to the left. The blade turns counter-clockwise seen from
// above. Azimuth is measured from +x toward +y.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "units/arc.hpp"
#include "blade/blade.hpp"
#include "blade/restitution.hpp"

namespace j232::scenario {

// Angles given in degrees are held as radians exactly (30 deg prints back as 30 deg).
inline constexpr double kDegree = std::numbers::pi / 180;

struct NailSpec {                    // uncoated 6d steel box nail
  double length = 0.0508;            // 2 in
  double diameter = 0.00251;         // 0.099 in shank
  double mass = 0.0020;              // 2.0 g
  double length_tolerance = 0.0008;  // +/- (uniform)
  double mass_tolerance = 0.0001;    // +/- (uniform): 1.9-2.1 g
};

struct FeedStation {
  std::size_t spindle = 0;  // which spindle's blade it feeds (J232 feeds every blade)
  double radius = 0.0;      // from that spindle's axis, m
  double azimuth = 0.0;     // about that axis, from +x, rad
};

struct FeedSpec {
  int nails = 150;
  // Nails go to stations in turn. As written; none written: one per spindle, 2 in inside its
  // tip circle, in front (Scenario::feed_station).
  std::optional<std::vector<FeedStation>> stations;
  double drop_height = 0.30;          // funnel outlet above the top of the blade, m
  double outlet_diameter = 0.025;     // funnel outlet, m: uniform position within it
  double outlet_speed_max = 0.5;      // speed leaving the outlet, uniform in [0, max], m/s
  double tilt_max = 5 * kDegree;      // nail axis within this cone about vertical
  double ground_speed = 0.0;          // mower travel speed; the nail drifts backward relative to the mower, m/s
};

// The blade near its cutting edge (docs/model.md §5.1a): what decides the direction of
// the impulse on a nail. Defaults are estimates (docs/model.md §8).
struct EdgeSpec {
  enum class Side { Top, Bottom };
  double bevel_angle = 30 * kDegree;  // between the bevel face and the blade plane, rad; 90 deg: square edge
  Side bevel_side = Side::Top;  // the face the bevel is ground on (top: the sharp edge on the bottom face)
  double width = 0.100;         // the plate behind the edge, m
  double sail_height = 0.0;     // the turned-up trailing strip, m above the top face (0: none)
  double sail_angle = 45 * kDegree;   // the sail against the blade plane, rad
  double friction = 0.4;        // nail on blade, Coulomb (steel on steel)
};

struct BladeGeometry {
  double height = 0.076;     // blade plane above ground, m (3 in)
  double thickness = 0.006;  // m
  EdgeSpec edge;
};

// One spindle of the deck and its blade. A scenario with [blade] has one, at the origin.
struct SpindleSpec {
  std::string blade_name;  // its [blades.NAME], or empty for an inline blade
  blade::Blade blade;
  BladeGeometry geometry;
  double x = 0.0, y = 0.0;  // the spindle's axis, m
  int sense = +1;           // +1 counter-clockwise seen from above, -1 clockwise
  // The blade's angle at each nail's time 0: a fixed offset from the deck's (timed
  // spindles, geared or on a timing belt) or none (untimed: independent and random).
  std::optional<double> phase;
  double reach() const { return std::hypot(x, y) + blade.tip_radius(); }  // from the origin
};

// A polyline in plan, (x, y) in m.
using PlanPath = std::vector<std::array<double, 2>>;

struct OpeningSpec {  // a discharge opening: the skirt is cut away between two azimuths
  std::string name = "discharge";
  units::Arc azimuth;  // about the origin, counter-clockwise from -> to
  std::optional<double> top;  // the opening's upper edge above ground, m, as written; none: the deck plate (HousingSpec::opening_top)
  // An optional chute: a hood of steel plate from the opening's edges straight outward
  // (along the opening's middle azimuth) for chute_length, its roof sloping from the
  // opening's top to chute_end_top, its side walls down to the skirt's bottom.
  double chute_length = 0.0;   // 0: no chute
  std::optional<double> chute_end_top;  // roof height at the chute's mouth, as written; none: the opening's top (HousingSpec::chute_end_top)
};

struct GuardSpec {  // a chain curtain, or a belting flap
  std::string name = "guard";
  // Chains: a porous curtain (openness, pass_speed_factor). A flap: a solid plate hinged at
  // its top edge that a nail swings as it strikes it (docs/model.md §5.3): its thickness,
  // density, and the width that swings as one (0: the whole flap).
  enum class Kind { Chains, Flap } kind = Kind::Chains;
  double thickness = 0.006;  // m, flap: belting (estimate: 1/4 in conveyor belting)
  double density = 1200;     // kg/m^3, flap: rubber belting (estimate: 1100-1400 for rubber compounds)
  double panel_width = 0.0;  // m, flap: the width that swings as one plate (0: the whole flap)
  // Where it hangs: below the skirt along the deck's outline between two azimuths (rad,
  // counter-clockwise from -> to), or, when `along` is given, along that polyline from
  // `top` down to `bottom` (a curtain on its own bracket; any deck, meshes included).
  units::Arc azimuth;
  PlanPath along;
  std::optional<double> top;       // upper edge along a polyline, m, as written; none: the deck plate (HousingSpec::guard_top)
  double bottom = 0.010;           // lower edge above ground, m
  double openness = 0.35;          // probability a nail passes between the links
  double pass_speed_factor = 0.7;  // speed kept when passing
  double restitution = 0.2;        // bounce off the curtain
  double friction = 0.5;
};

struct DeflectorSpec {  // a solid vertical panel inside or outside the skirt
  std::string name = "deflector";
  // On an arc about the origin (radius, azimuths), or along a polyline when `along` is given.
  units::Arc azimuth;
  double radius = 0.0;
  PlanPath along;
  double bottom = 0.0, top = 0.0;
};

struct HousingSpec {
  std::optional<double> deck_radius;                                         // as written; none: the blades' reach + margin (Scenario::deck_radius)
  double skirt_bottom = 0.038;                                               // above ground (skid shoes 1.5 in below the blade)
  double skirt_depth = 0.175;                                                // skirt bottom to deck plate
  blade::Restitution restitution = blade::Restitution::default_power_law();  // steel on steel
  double friction = 0.4;
  double margin = 0.050;  // deck outline outside every tip circle (several spindles)
  std::vector<OpeningSpec> openings;
  std::vector<GuardSpec> guards;
  std::vector<std::string> absent_guards;  // guards given with present = false: described, not fitted
  std::vector<DeflectorSpec> deflectors;

  // The deck plate's height above ground (the skirt's top), and the heights derived from it
  // where the file leaves them out: an opening's top, its chute's mouth (the opening's top),
  // and a curtain's top along a polyline.
  double plate_height() const { return skirt_bottom + skirt_depth; }
  double opening_top(const OpeningSpec& o) const { return o.top.value_or(plate_height()); }
  double chute_end_top(const OpeningSpec& o) const { return o.chute_end_top.value_or(opening_top(o)); }
  double guard_top(const GuardSpec& g) const { return g.top.value_or(plate_height()); }
};

struct GroundSpec {  // what the mower stands on: `kind` sets the rest (scenario/ground_kinds.hpp)
  std::string kind = "turf";
  // Normal restitution depends on the impact angle (docs/model.md §5.3): rockfall field
  // data (Wyllie 2014) fit e_n = 19.5 theta^-1.03 (theta in degrees between the path and
  // the surface), so shallow impacts keep more of their normal speed. j232 keeps the
  // exponent and scales the law to `restitution` at a perpendicular impact, capped at
  // `max_restitution` (the law passes 1 at grazing angles; a bounce off turf loses energy).
  double restitution = 0.15;       // e_n at a 90 deg (perpendicular) impact
  double angle_exponent = 1.03;    // 0: one constant e_n at every angle
  double max_restitution = 0.8;    // cap at shallow impacts (estimate)
  double friction = 0.5;
  double roughness = 10 * kDegree;  // std. dev. of the local surface normal's tilt, rad
  // A round object rolling on it (a field's steel ball, or stones the scenario calls round)
  // slows by this many g once it rolls without slipping (a golf ball on a green about 0.05-0.09;
  // a mowed verge's taller grass more: an estimate). Field scenarios only: nails do not roll.
  double rolling_resistance = 0.3;
  // Young's penetrability number S of the soil under it (0: a nail is taken not to sink in).
  // A nail arriving point-first sinks in by Young's equation; deep enough, it stays
  // (flight/penetration.hpp, docs/model.md §5.3a).
  double penetrability = 0.0;
  // e_n for an impact whose path makes `angle` (rad, 0-pi/2) with the surface.
  double restitution_at(double angle) const {
    if (angle_exponent == 0.0) return restitution;
    const double ratio = std::max(angle, 1e-3) / (0.5 * std::numbers::pi);
    return std::min(max_restitution, restitution * std::pow(ratio, -angle_exponent));
  }
};

// What a mesh file is in the scene (its `label` key).
enum class MeshLabel { Ground, Housing, Deflector, Guard, Target, OperatorZone };
inline constexpr std::array<const char*, 6> kMeshLabelNames = {"ground", "housing", "deflector", "guard", "target", "operator_zone"};
inline const char* mesh_label_name(MeshLabel l) { return kMeshLabelNames[static_cast<std::size_t>(l)]; }
// The board (either part of it: a target mesh may carry the operator zone separately).
inline bool is_board(MeshLabel l) { return l == MeshLabel::Target || l == MeshLabel::OperatorZone; }

struct MeshFile {
  std::string path;
  std::optional<int> line;  // of its [[meshes]] table's path, for errors about what the mesh holds
  MeshLabel label = MeshLabel::Housing;
  double scale = 1.0;  // file units to metres
  // Guard properties when label is Guard.
  GuardSpec guard;
};

struct TargetSpec {
  // A ring about the deck's centre at `distance` outside the farthest tip, or a wall that
  // follows the deck: `distance` outside every spindle's tip circle (their convex hull).
  enum class Shape { Circle, Outline } shape = Shape::Circle;
  double distance = 0.610;  // board wall outside the tip circle, m
  double bottom = 0.0;      // board bottom above ground, m
  std::optional<double> top;  // as written; none: the blades' plane + 0.610 m (Scenario::target_top)
  int segments = 360;       // around the ring
};

struct OperatorZoneSpec {
  enum class Kind { Sector, Derived } kind = Kind::Derived;
  // Sector: an azimuth range and height range of the target board.
  units::Arc azimuth;
  double bottom = 0.0, top = 0.0;
  // Derived (docs/model.md §5.4): seated operator; seat index point position.
  double seat_x = 2.0, seat_y = 0.0, seat_z = 0.90;
  double shoulder_height = 0.646;  // above the seat
  double shoulder_half_width = 0.20;
  double reach = 0.942;  // extended reach, 95th-percentile male
  double knee_height = 0.604;
};

struct BoardSpec {                           // double-wall 350# corrugated board
  double puncture_energy_per_width = 110.0;  // J/m
  double hit_fraction = 0.3;                 // hit threshold / puncture threshold
  // How deep the nail crushes the board as it marks it: the part of the nail within this
  // depth of its first touch is what presses on the board (about the board's thickness).
  double crush_depth = 0.007;  // m: the board's caliper, about 7 mm
};

struct CriteriaSpec {  // report 445-1, Chapter 3 (SAE J232)
  double hits_zone = 0.20, punctures_zone = 0.005, hits_outside = 0.15, punctures_outside = 0.05;
  // SAE J232 counts only marks above the plane of the blade tip circle (report 445-1,
  // Ch. 3). None: that plane (the blade height); a value departs from J232 and says so.
  std::optional<double> counted_height;
  // The limits SAE J232 sets (the defaults above): true when any differs.
  bool limits_depart_from_j232() const;
  enum class Denominator { NailsFed, Marks } denominator = Denominator::NailsFed;
  // The verdict: the mower passes when its estimated probability of passing one
  // physical test is at least this. A program default, not part of SAE J232.
  double required_pass_probability = 0.9;
};

struct AirSpec {
  bool drag = true;
  double density = 1.2;
  double cd_normal = 1.0;  // cross-flow on the shank
  double cd_axial = 0.8;   // end-on
  // A fast-spinning nail's drag averaged over its axis's turn; false: the drag as the axis
  // stands, with steps of at most 0.3 rad of turn (a reference, about 90 times slower).
  bool spin_average = true;
};

// How a contact's restitution coefficient is read: Stronge's energetic coefficient (the
// restitution phase's normal work e^2 times the compression's, friction integrated along the
// normal impulse) or Poisson's impulse ratio (the earlier law, slip held in its first direction).
enum class RestitutionLaw { Energetic, Poisson };

// How contacts with the scene at one instant are resolved (docs/model.md §5.3): one after the
// other (each by the impulse law), or together (Moreau's: one impulse per contact, found at
// once with Newton's restitution at each and Coulomb friction).
enum class ContactModel { Sequential, Simultaneous };

// How a knife's push on a sphere is followed (docs/model.md §9.1): once the body would be
// caught again before it could part from the face by the touch tolerance, held on the face
// and slid along it under the knife's push and Coulomb friction until it lifts off or leaves
// the face (the default); or contact by contact, each an impulse with Coulomb friction, as
// any blade contact (the chain of impacts the held slide replaces, to compare against).
// A capsule (a nail) is always followed contact by contact.
enum class BladePush { Held, Impacts };

struct RunSpec {
  long long replicates = 1000;
  unsigned long long seed = 1;
  int threads = 0;                          // 0: all cores
  // Which P(pass) estimate the verdict rests on (docs/model.md §5.6b): the narrower of the
  // replicates' share and the exact sum over every nail, or one of them.
  enum class Estimator { Narrower, Replicates, EveryNail };
  Estimator estimator = Estimator::Narrower;
  // Stop rules (batches until met, or max_replicates): the verdict's P(pass) interval this
  // narrow, or wholly on one side of the required probability.
  std::optional<double> target_half_width;
  bool until_settled = false;
  long long max_replicates = 100000;
  double chord_tolerance = 0.001;  // max sag of a flight chord, m
  // s of flight per object: as written; none: 3 s a nail of the J232 test, 20 s an object
  // thrown across a field (Scenario::time_limit).
  std::optional<double> time_limit;
  // Bounces of one flight: as written; none: Scenario::max_bounces (a tumbling rod bounces
  // about 15 times a flight; nails riding round a closed skirt, hundreds).
  std::optional<int> max_bounces;
  // Gentle contacts (approaching slower than a fall through the object's own diameter): the
  // micro-impacts by which a sustained contact (sliding along a skirt's foot, under a flap,
  // on the turf) is followed. Thousands in a long slide; the cap stops a contact that no
  // longer moves on.
  int max_gentle_contacts = 100000;
  // Blade strikes of one nail, and contacts of one pass of an edge, beyond which a nail is cut
  // off (counted, never silent): guards against a flight that no longer moves on. A knife
  // pushing a nail or a stone along its face touches it again every few to few tens of µs
  // until the body slides off its tip, within about a turn (docs/model.md §5.1): a 97 mm
  // cobble pushed 0.61 -> 0.74 m out along a 990 rpm knife took 405 contacts about 11 µs
  // apart; the shipped J232 runs' longest passes take 608 and 956. 20 000 contacts cover a
  // whole turn at 990 rpm (61 ms) with contacts 3 µs apart.
  // max_strikes as written; none: Scenario::max_strikes.
  std::optional<int> max_strikes;
  int max_contacts_per_pass = 20000;
  double rest_speed = 0.3;  // m/s: slower after a bounce is at rest
  // How blade contacts are searched: conservative advancement, or the fixed-step reference
  // it is validated against (about 300 times slower; docs/validation.md).
  bool reference_contact_search = false;
  // How a contact's restitution is read (docs/model.md §5.1c): Stronge's energetic law,
  // friction integrated along the impulse; or the Poisson law of earlier versions, kept to
  // compare against.
  RestitutionLaw restitution_law = RestitutionLaw::Energetic;
  ContactModel contact_model = ContactModel::Sequential;  // [contacts] model
  BladePush blade_push = BladePush::Held;                 // [contacts] blade_push
};

// An uncertainty study of the scenario (`j232 uq`, docs/model.md §6b): inputs varied
// uniformly between two values, each with the basis of its range. `parameter` is a sweep
// parameter (`restitution`, `bevel_angle`, ...) or any dotted key of the file; `low` and
// `high` are written as that key takes them ("0.7", "0 deg"). No inputs: j232 uq uses its
// default set of the estimated inputs.
struct UncertainInput {
  std::string parameter, low, high, basis;
  std::optional<int> line;
  // How the value is spread over [low, high] (docs/model.md §6b): "uniform"; "triangular"
  // with its `mode` (default the midpoint); "normal" about the midpoint with `sd` (default a
  // quarter of the range), truncated to the range; "loguniform" (low above zero): uniform in
  // the logarithm, for a factor known only to within a ratio (a density of stones).
  // mode and sd are written like low.
  std::string distribution = "uniform";
  std::string mode, sd;
  // A discrete input instead of a range (rotation sense, a choice of guard): the values the
  // key takes, as written, each drawn with equal probability; low and high are then unused.
  std::vector<std::string> values;
};
struct UncertaintySpec {
  std::vector<UncertainInput> inputs;
  long long base_draws = 256;  // N of the Saltelli scheme: N (k + 2) assessments (fewer only on request: indices at N = 32 are noise)
  long long replicates = 50;   // per assessment (its P(pass) from every nail is smooth; see docs/model.md §6b)
  // A field scenario's assessments: objects simulated in each (none: the smaller of
  // field.objects_simulated and 20 000).
  std::optional<long long> objects;
};

// A mower at work over a field strewn with objects (`j232 hazard`, docs/model.md §9): no
// board; the ground around the mower and vertical planes beside it are what is tallied.
// Defaults are estimates unless a source is named (docs/model.md §8).
struct FieldObjectSpec {
  std::string name;                       // as reports name it ("gravel")
  enum class Kind { Stone, SteelBall } kind = Kind::Stone;
  // Size: the diameter of the sphere of the same volume, lognormal by its median and
  // geometric standard deviation (1: all the same), cut to [min_size, max_size].
  double median_size = 0.015, spread = 1.5, min_size = 0.005, max_size = 0.040;  // m
  double density = 2650;                   // kg/m^3 (quartz and granite, 2600-2700)
  double per_area = 0.5;                   // objects per m^2 of ground mowed
  double embedment = 0.25;                 // share of its size sunk into the turf (0: lying on top)
  // On the blade, Poisson's: stone on steel 0.5 (an estimate); none: the scenario's
  // [restitution] (steel on steel, a steel ball's default).
  std::optional<double> restitution = 0.5;
  double friction = 0.4;                   // on the blade, Coulomb
  double drag_coefficient = 0.6;           // on its cross-section (a smooth sphere: 0.47)
  // On the ground it rolls (a ball; a rounded stone) rather than skids (an angular stone, the
  // default for stones): slipping at the turf's friction until it rolls, then slowed by its
  // rolling resistance (GroundSpec::rolling_resistance). One that skids does not roll along the
  // mower's steel either: it leaves each contact there without spin.
  bool rolls = false;
};

struct FieldPlaneSpec {  // a vertical plane beside the mower's path: a lane, a fence, a footpath
  std::string name;
  enum class Side { Left, Right, Front, Rear } side = Side::Right;
  double distance = 3.0;  // from the mower's centre line (left, right) or centre (front, rear), m
  enum class Receptor { Person, Vehicle } receptor = Receptor::Person;
};

struct FieldSpec {
  bool present = false;                       // the scenario has a [field] table
  double ground_speed = 8.0 / 3.6;            // m/s, the mower's travel (8 km/h: an estimate)
  // The air the blades draw up under the deck, at the turf (an estimate; 0: none): an object
  // whose drag in it, 1/2 rho u^2 C_d A, exceeds its weight is lifted into the blades' plane.
  double updraft_speed = 0.0;
  // What holds an object up above the plane the mower's wheels ride on (crowns and clods of
  // the ground, thatch, clumps, stones on stones): the height of its resting level, drawn
  // for each object from an exponential distribution of this mean (m; an estimate, docs/model.md
  // §9). 0: every object lies on that plane.
  double support_height = 0.010;
  // The supports' distribution of that mean: exponential (many low, a long tail of tall
  // ones), or half-normal (fewer tall ones: sigma = mean sqrt(pi / 2)). Not surveyed: at high
  // cuts the tail decides how many reach (docs/model.md §9.1).
  enum class SupportShape { Exponential, HalfNormal } support_shape = SupportShape::Exponential;
  std::vector<FieldObjectSpec> objects;
  std::vector<FieldPlaneSpec> planes;
  double range = 100;                         // m: the ground tallied out to this in every direction
  double cell = 1.0;                          // m: the tally's grid
  long long objects_simulated = 100000;       // objects met by the blades in one hazard run
  // A person (DDESB Technical Paper 12): struck hazardously by an object of at least
  // person_energy; presented area; one hazardous impact per acceptable_area is acceptable.
  double person_energy = 79.0;                // J (58 ft lb)
  double presented_area = 0.58;               // m^2
  double acceptable_area = 55.74;             // m^2 (600 ft^2)
  double person_height = 1.8;                 // m: the band a person stands in at a plane
  // A season's exposure (stated inputs; 1 and 1: a season of one pass, one person): the passes
  // the mower makes along the path, and the people at a person plane at each pass.
  long long passes_per_season = 1;
  double people_per_pass = 1;
  // A vehicle in a lane: hazardous impacts on the windshield's band (estimates).
  double vehicle_energy = 2.0;                // J
  double windshield_bottom = 0.9, windshield_top = 1.5;  // m above ground
};

struct Scenario {
  std::string file;
  std::string title;
  // Inputs the scenario's author marks as estimates (`estimates = ["housing.skirt_bottom"]`):
  // each key and its value as written, listed among the report's assumptions.
  struct MarkedEstimate {
    std::string key, value;
  };
  std::vector<MarkedEstimate> estimates;
  // What the reader noticed in values it accepted but a reader of the file might take
  // otherwise (a guard named as a flap without `kind`, read as a chain curtain), each with its
  // file, line and key: shown among a result's warnings.
  std::vector<std::string> notes;
  std::vector<SpindleSpec> spindles = std::vector<SpindleSpec>(1);     // at least one; [blade]: one at the origin
  blade::Restitution restitution = blade::Restitution::constant(0.9);  // nail on blade
  NailSpec nail;
  FeedSpec feed;
  HousingSpec housing;
  GroundSpec ground;
  TargetSpec target;
  std::vector<MeshFile> meshes;  // when present they replace the generated housing and targets
  OperatorZoneSpec zone;
  BoardSpec board;
  CriteriaSpec criteria;
  AirSpec air;
  RunSpec run;
  UncertaintySpec uncertainty;
  FieldSpec field;  // present: a hazard scenario (j232 hazard), not a J232 test

  // Marks below this height (m above ground) are not counted (CriteriaSpec::counted_height).
  double counted_height() const { return criteria.counted_height.value_or(blade_plane()); }
  // The highest blade plane (J232 counts marks above the blade tip-circle plane).
  double blade_plane() const;
  // How far the blades reach from the origin (the board ring is centred there).
  double reach() const;
  // The fastest blade tip.
  double tip_speed() const;
  // In a field: the lowest blade's lower face above the turf (an object must stand above it
  // to be struck unless the updraft lifts it), the gap objects pass under into the deck (the
  // skirt's, or a front opening's; none for a mesh deck, whose front is not known), and the
  // largest object of a kind the updraft `u` lifts (its drag, 1/2 rho u^2 C_d A, above its
  // weight: sizes up to 3 rho C_d u^2 / (4 rho_s g)).
  // A round deck's radius (one spindle): housing.deck_radius as written, else the blades'
  // reach + housing.margin.
  double deck_radius() const { return housing.deck_radius.value_or(reach() + housing.margin); }
  // A flight's time limit: run.time_limit as written, else 3 s a nail, 20 s a field's object.
  double time_limit() const { return run.time_limit.value_or(field.present ? 20.0 : 3.0); }
  // A flight's bounces and blade strikes at most: run.max_bounces and run.max_strikes as
  // written, else 400 bounces a nail and ten times that a field's object, and as many strikes
  // as one whole push along a knife takes (run.max_contacts_per_pass) and 500 besides (a
  // field's object: 5 000). A stone too large for the gap under a chained deck rattles inside
  // for seconds, struck again and again, before it leaves through the chains (a cobble on
  // the shipped shoulder: 400 bounces in 3.5 s of its 20 s); the limits are a guard against a
  // flight that no longer moves on, and the time limit bounds a field's flight.
  int max_bounces() const { return run.max_bounces.value_or(field.present ? 4000 : 400); }
  int max_strikes() const { return run.max_strikes.value_or(run.max_contacts_per_pass + (field.present ? 5000 : 500)); }
  // The target board's top: target.top as written, else 0.610 m above the blades' plane.
  double target_top() const { return target.top.value_or(blade_plane() + 0.610); }
  // The feed stations (feed.stations as written, else one per spindle, 2 in inside its tip
  // circle, in front): how many, station i (allocation-free, for the per-nail path), and all.
  std::size_t feed_station_count() const { return feed.stations ? feed.stations->size() : spindles.size(); }
  FeedStation feed_station(std::size_t i) const;
  std::vector<FeedStation> feed_stations() const;
  double lowest_blade_face() const;
  std::optional<double> front_gap() const;
  double lifted_up_to(const FieldObjectSpec& o, double drag_coefficient, double u) const;
  // Where a feed station drops its nails, in the world frame (m).
  double station_x(const FeedStation& f) const { return spindles[f.spindle].x + f.radius * std::cos(f.azimuth); }
  double station_y(const FeedStation& f) const { return spindles[f.spindle].y + f.radius * std::sin(f.azimuth); }
};

}  // namespace j232::scenario
