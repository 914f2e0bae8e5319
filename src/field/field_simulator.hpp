#pragma once
// One object of the field from the moment the mower's blades reach it to its end
// (docs/model.md §9): which object the mower meets (its kind and size from the field's
// objects, where across the cut it lies), the blade's first touch on it through the same
// contact search and impulse as the J232 nail's strike, and its flight through the deck,
// the guards and over the turf, told to an observer that tallies it.
//
// Frame: the mower's (x forward, y to the left, z up, origin on the ground at the deck's
// centre), travelling at the field's ground speed along +x; objects come at it at that
// speed. Time 0 is when the object enters the first blade's reach.
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "flight/mower.hpp"
#include "flight/nail_flight.hpp"
#include "projectile/projectile.hpp"
#include "scenario/scenario.hpp"
#include "strike/spindle.hpp"

namespace j232::field {

using Vec3 = Eigen::Vector3d;

// One object the blades meet.
struct Encounter {
  std::size_t kind = 0;                // field.objects index
  projectile::Projectile body;        // a sphere
  double lateral = 0;                  // y of its centre, m
  double support = 0;                  // z of the level it rests on (field.support_height), m
  double height = 0;                   // z of its centre (on its support, sunk by its embedment), m
  bool lifted = false;                 // drawn up by the updraft: it meets the blades in their plane
};

enum class ObjectFate : std::uint8_t {
  NotReached,  // the blades passed over it (its top below their lower faces) or it lay outside their reach
  NotThrown,   // touched, but given no energy (it was not thrown)
  Thrown,      // thrown: its flight ended at rest, or it left the tallied square
  CutOff       // thrown, and cut off still moving by a limit (time, bounces, steps) or a non-finite state
};
inline constexpr int kObjectFates = 4;
// Counted as thrown: its flight ended, or a limit cut it off (the run's invalidity says how many).
inline bool counted_thrown(ObjectFate f) { return f == ObjectFate::Thrown || f == ObjectFate::CutOff; }
const char* object_fate_name(ObjectFate f);

struct ObjectOutcome {
  Encounter encounter;
  ObjectFate fate = ObjectFate::NotReached;
  std::size_t spindle = 0;     // the spindle that threw it
  double strike_time = 0;      // s: its first strike (the observer's frame is the ground's then)
  double exit_speed = 0;       // m/s as it leaves the blade (its last contact before anything else), ground frame
  double launch_elevation = 0; // rad, of that velocity
  // m/s off its last blade strike, ground frame: a thrown object is often struck again, and
  // faster, inside the deck (the speed it leaves with is that, not the first strike's)
  double last_strike_speed = 0;
  bool pressed = false;         // its first strike drove it into the soil and the knife rode over it
  flight::FlightResult flight;  // when thrown
};

class FieldSimulator {
 public:
  // Throws scenario::InputError for a scenario without [field] or an unsound blade.
  FieldSimulator(const scenario::Scenario& s, scene::Engine engine = scene::default_engine());

  // Object `index` of the run (a pure function of the scenario's seed and the index): of
  // kind index mod kinds() (each kind its own stratum), its size drawn from the sizes that
  // can reach a blade (standing up to the lowest blade's lower face, or light enough for the
  // updraft to lift), which are reach_share(kind) of the kind's objects. The
  // observer (may be null) is told of its flight; `prepare` is called first with the thrown
  // object's mass and strike time, so that it can judge energies and move to the ground's frame.
  struct Watch {
    virtual ~Watch() = default;
    virtual void thrown(double mass, double strike_time) = 0;
    virtual flight::FlightObserver* observer() = 0;
  };
  // `events`: when set, every event of its flight is appended (j232 hazard --replay).
  ObjectOutcome simulate(std::uint64_t index, Watch* watch = nullptr, std::vector<flight::FlightEvent>* events = nullptr,
                         std::vector<flight::FlightStretch>* stretches = nullptr) const;

  const scenario::Scenario& scenario() const { return scenario_; }
  const flight::Mower& mower() const { return *mower_; }
  // The width the blades cut (the union of their tip circles across the travel), m, and
  // where it lies. Objects of a kind are met across it widened by half their largest size
  // each side (a blade reaches an object whose centre lies that far outside its tip circle).
  double cut_from() const { return cut_from_; }
  double cut_to() const { return cut_to_; }
  double met_width(std::size_t kind) const { return cut_to_ - cut_from_ + scenario_.field.objects[kind].max_size; }
  std::size_t kinds() const { return spindles_.size(); }
  // Objects of a kind the mower meets per metre travelled, and the share of them whose
  // size lets them reach a blade (the rest pass under untouched).
  double objects_per_metre(std::size_t kind) const;
  double reach_share(std::size_t kind) const { return sizes_[kind].share; }
  // A bound on the kinetic energy any object of a kind can have after the blades threw it:
  // its largest size that reaches a blade, at (1 + e) <= 2 times the fastest tip speed with a
  // margin, plus the mower's travel and a fall of 5 m. A kind whose bound is below an energy
  // threshold can make no event of it (its stratum does not widen that figure's interval).
  double energy_bound(std::size_t kind) const { return sizes_[kind].energy_bound; }
  // Objects the mower meets per metre travelled (every kind).
  double objects_per_metre() const;

 private:
  Encounter sample(std::size_t kind, random::Stream& rng) const;  // one object of a kind, among its sizes that reach
  double drawn_size_probability(std::size_t kind, random::Stream& rng) const;  // its size's place on the lognormal's axis
  scenario::Scenario scenario_;
  std::unique_ptr<flight::Mower> mower_;
  std::vector<std::vector<strike::Spindle>> spindles_;  // per kind: its restitution and friction on the blades
  std::vector<flight::Drag> drag_per_unit_;             // per kind, for a 1 m sphere (scaled by 1 / size)
  double cut_from_ = 0, cut_to_ = 0;
  // Per kind, the sizes that can reach a blade, on the lognormal's probability axis p.
  // Without support (field.support_height 0): pieces [p_low, p_high) (at most two: the lifted
  // small ones, the tall ones), each reaching for certain. With support: the lifted piece,
  // and above it the supported sizes, each reaching with the probability its support puts
  // its top between the blade's lower face and the deck's front gap (held_up); drawn by
  // rejection under a piecewise-constant envelope over a grid of p (exact, docs/model.md §9).
  struct ReachableSizes {
    std::vector<std::array<double, 2>> pieces;
    double share = 0;
    double energy_bound = 0;  // J
    // With support: the grid over [supported_from, p_high] and its envelope's cumulative mass.
    std::vector<double> grid, envelope, cumulative;
    double lifted_mass = 0, supported_mass = 0;  // of p; their sum / the kind's whole is the share
  };
  std::vector<ReachableSizes> sizes_;
  // The probability that an object of a kind and size rests high enough for its top to
  // stand above the blade's lower face and low enough to pass under the deck's front, and
  // the band of support heights that does it.
  struct SupportBand {
    double from = 0, to = HUGE_VAL;  // m
    double probability = 0;
  };
  SupportBand held_up(std::size_t kind, double size) const;
};

}  // namespace j232::field
