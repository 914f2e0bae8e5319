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
  // stratum index mod strata() (each kind's reachable sizes split into size strata), its size
  // drawn from the stratum's sizes that can reach a blade (standing up to the lowest blade's
  // lower face, or light enough for the updraft to lift). The
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
  double reach_share(std::size_t kind) const;
  // The strata objects are drawn from (docs/model.md §9): each kind's sizes that reach a
  // blade, split at sizes that give each stratum about an equal share of their mass
  // (kSizeStrata of them, one for a kind of one size), so that the rare heavy objects that carry a
  // hazardous energy are drawn as often as the many light ones; every stratum is given the
  // same number of objects and weighted by its share.
  struct SizeStratum {
    std::size_t kind = 0;
    std::size_t first_cell = 0, end_cell = 0;  // its cells of the kind's reachable sizes
    double share = 0;                          // of the kind's objects met: those of its sizes that reach a blade
    double smallest = 0, largest = 0;          // m
    // A bound on the kinetic energy any of its objects can have after the blades threw it
    // (its largest at 2.2 times the fastest tip speed, plus the mower's travel and a fall of
    // 5 m): a stratum whose bound is below an energy threshold can make no event of it, and
    // does not widen that figure's interval.
    double energy_bound = 0;  // J
  };
  static constexpr std::size_t kSizeStrata = 4;
  std::size_t strata() const { return strata_.size(); }
  const SizeStratum& stratum(std::size_t s) const { return strata_[s]; }
  double energy_bound(std::size_t kind) const;  // the largest of its strata's
  // Objects the mower meets per metre travelled (every kind).
  double objects_per_metre() const;

 private:
  // Per kind, the sizes that can reach a blade, on the lognormal's probability axis p, as
  // cells: without support (field.support_height 0) the pieces that reach for certain (the
  // lifted small ones, the tall ones), in cells of reach 1; with support, the lifted piece so,
  // and above it a grid of cells on which each size reaches with the probability its support
  // puts its top between the blade's lower face and the deck's front gap (held_up), with that
  // probability's integral over the cell (Simpson) and its largest value there (envelope).
  // Drawn by rejection under the envelope (exact, docs/model.md §9).
  struct ReachCell {
    double from = 0, to = 0;  // p
    double mass = 0;          // the reach probability's integral over [from, to)
    double envelope = 1;      // its largest value there
    bool certain = true;      // reach probability 1 throughout
  };
  struct ReachableSizes {
    std::vector<ReachCell> cells;
    std::vector<double> cumulative;  // the envelopes' masses before each cell (cells + 1)
    double share = 0;                // the whole reach mass over the kind's
  };
  Encounter sample(const SizeStratum& stratum, random::Stream& rng) const;  // one object of a stratum
  double drawn_size_probability(const SizeStratum& stratum, random::Stream& rng) const;  // its size's place on the lognormal's axis
  void add_size_strata(std::size_t kind, double whole, const ReachableSizes& reach);
  scenario::Scenario scenario_;
  std::unique_ptr<flight::Mower> mower_;
  std::vector<std::vector<strike::Spindle>> spindles_;  // per kind: its restitution and friction on the blades
  std::vector<flight::Drag> drag_per_unit_;             // per kind, for a 1 m sphere (scaled by 1 / size)
  double cut_from_ = 0, cut_to_ = 0;
  std::vector<ReachableSizes> sizes_;
  std::vector<SizeStratum> strata_;
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
