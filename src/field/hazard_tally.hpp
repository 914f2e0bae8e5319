#pragma once
// What a hazard run counts (docs/model.md §9b), in the ground's frame at each object's
// first strike (the mower's position then is the origin; the mower travels along +x):
// where objects first come down around the mower and where they strike the ground
// hazardously (with at least a person's hazardous energy), on a square grid out to the
// field's range; the hazardous impacts at each distance to the sides (a strip along the
// mower's path) and ahead of and behind it (on its line), per object with their squares
// for intervals; and each vertical plane's crossings by height and energy.
//
// Everything is a whole count, so tallies merge exactly in any order: the run is
// bit-identical on any number of threads.
#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "field/field_simulator.hpp"
#include "flight/nail_flight.hpp"
#include "scenario/scenario.hpp"

namespace j232::field {

// A per-object count summed over objects, with its square (its variance for intervals).
struct CountSum {
  std::uint64_t sum = 0, squares = 0;
  void add(std::uint64_t c) { sum += c, squares += c * c; }
  void merge(const CountSum& o) { sum += o.sum, squares += o.squares; }
};

struct HazardLayout {
  double range = 100, cell = 1;
  int half_cells = 100;  // cells from the origin to the square's edge
  int cells() const { return 2 * half_cells; }
  double ground_speed = 0;
  double person_energy = 79, person_height = 1.8;
  double vehicle_energy = 2, windshield_bottom = 0.9, windshield_top = 1.5;
  std::vector<scenario::FieldPlaneSpec> planes;
  static HazardLayout of(const scenario::FieldSpec& f);
  // The cell of a ground point, or -1 outside the square.
  int cell_of(double x, double y) const;
};

// Plane crossings by height: 0.25 m bands from the ground to 4 m, and above.
inline constexpr int kHeightBands = 17;
inline constexpr double kHeightBand = 0.25;
// Kinetic energies: bins of a tenth of a decade from 1 mJ to 10 kJ (and below, above).
inline constexpr int kEnergyBins = 72;
int energy_bin(double joules);
double energy_bin_low(int bin);  // J, the bin's lower edge (bin 0: 0)

struct PlaneTally {
  std::array<std::uint64_t, kHeightBands> by_height{};  // every crossing
  std::array<std::uint64_t, kEnergyBins> by_energy{};   // every crossing, by its kinetic energy
  CountSum hazardous;  // per object: crossings within the receptor's band with at least its energy
  void merge(const PlaneTally& o);
};

class HazardTally {
 public:
  explicit HazardTally(const HazardLayout& layout);
  HazardLayout layout;

  std::uint64_t objects = 0;
  std::array<std::uint64_t, kObjectFates> fates{};
  std::array<std::uint64_t, flight::kCutOffReasons> cut_off_by{};
  std::uint64_t at_rest_under_deck = 0;       // thrown, and came to rest inside the deck's outline
  std::uint64_t left_square = 0;              // thrown beyond the tallied square (still moving or at rest)
  std::uint64_t landed_beyond_square = 0;     // first came down outside the square
  std::uint64_t hazardous_beyond_square = 0;  // hazardous ground impacts outside the square
  std::uint64_t overflow = 0;                 // objects with more hazardous impacts than an object's record holds
  // Objects a knife rode over (pressed into the soil) at least once (how much rests on that
  // rule), and objects pushed along by an arm at least once: held on a knife's face, or,
  // contact by contact ([contacts] blade_push = "impacts"), in a pass of more than 64 contacts
  // (docs/model.md §9.1).
  std::uint64_t ridden_over = 0, pushed_along = 0;
  std::vector<std::uint64_t> landings;   // [cell]: objects first coming down there (outside the deck)
  std::vector<std::uint64_t> hazardous;  // [cell]: ground impacts with at least the person's energy
  // Per distance bin k (k cells out): hazardous impacts in the strip beside the path at that
  // lateral distance (left, right), and on the mower's line (|y| < cell / 2) at that
  // distance or farther ahead (front) or behind (rear).
  std::array<std::vector<CountSum>, 4> directions;  // left, right, front, rear
  // Per distance bin k, left and right: hazardous crossings, below the person's height, of
  // the vertical plane along the path at (k + 1/2) cells (a person standing there is struck
  // by what flies or skids through, not only by what comes down).
  std::array<std::vector<CountSum>, 2> vertical;
  std::vector<PlaneTally> planes;
  std::array<std::uint64_t, 400> exit_speed{};       // 0.5 m/s bins: speed off the blade, ground frame
  std::array<std::uint64_t, 180> launch_elevation{};  // 1 deg bins from -90 deg
  std::array<std::uint64_t, 400> last_strike_speed{};  // 0.5 m/s bins: speed off the last blade strike, ground frame
  std::array<std::uint64_t, 2000> farthest{};          // 0.25 m bins: each thrown object's farthest ground contact from the origin
  double max_distance = 0;                             // m, of any ground contact

  void add(const ObjectOutcome& o);
  void merge(const HazardTally& o);
  void clear();  // every count back to zero, the layout kept
  std::size_t bytes() const;  // what its counts take (its grids, mostly)
  // The whole tally as bytes (a chunk's, sent to rank 0), appended to a message of several,
  // and read back from `at` on (moving it past the tally) into a tally of the same layout.
  std::string pack() const;
  void pack_at(std::string& out) const;
  void unpack_at(const std::string& bytes, std::size_t& at);

  // Every count of two tallies in step, once: merge, pack and unpack go through it, so none
  // of them can miss a count another has. `f(a, b)` is called with each count of `a` and the
  // same count of `b` (whole numbers, arrays and vectors of them, CountSums, and the
  // farthest distance, a double merged by its maximum).
  template <class A, class B, class F>
  static void zip(A& a, B& b, F&& f) {
    f(a.objects, b.objects);
    f(a.fates, b.fates);
    f(a.cut_off_by, b.cut_off_by);
    f(a.at_rest_under_deck, b.at_rest_under_deck);
    f(a.left_square, b.left_square);
    f(a.landed_beyond_square, b.landed_beyond_square);
    f(a.hazardous_beyond_square, b.hazardous_beyond_square);
    f(a.overflow, b.overflow);
    f(a.ridden_over, b.ridden_over);
    f(a.pushed_along, b.pushed_along);
    f(a.landings, b.landings);
    f(a.hazardous, b.hazardous);
    for (std::size_t d = 0; d < a.directions.size(); ++d) f(a.directions[d], b.directions[d]);
    for (std::size_t d = 0; d < a.vertical.size(); ++d) f(a.vertical[d], b.vertical[d]);
    for (std::size_t p = 0; p < a.planes.size(); ++p) {
      f(a.planes[p].by_height, b.planes[p].by_height);
      f(a.planes[p].by_energy, b.planes[p].by_energy);
      f(a.planes[p].hazardous, b.planes[p].hazardous);
    }
    f(a.exit_speed, b.exit_speed);
    f(a.launch_elevation, b.launch_elevation);
    f(a.last_strike_speed, b.last_strike_speed);
    f(a.farthest, b.farthest);
    f(a.max_distance, b.max_distance);
  }
};

// Watches one object at a time and adds what it did to a tally when told it ended.
class ObjectWatch final : public FieldSimulator::Watch, public flight::FlightObserver {
 public:
  explicit ObjectWatch(HazardTally& tally) : tally_(tally) {}
  void thrown(double mass, double strike_time) override;
  flight::FlightObserver* observer() override { return this; }
  void flew(double t0, const Vec3& p0, const Vec3& v0, double t1, const Vec3& p1, const Vec3& v1) override;
  void met_ground(double t, const Vec3& point, const Vec3& velocity, bool in_deck) override;
  // The object's outcome: adds its per-object counts and its fate to the tally.
  void finish(const ObjectOutcome& outcome);
  // The last object's own counts (after finish; zero for one not thrown): whether it first
  // came down outside the deck, its hazardous ground impacts anywhere outside the deck, and
  // per plane its crossings and hazardous crossings. For paired comparisons (j232 compare).
  bool landed_outside() const { return landed_; }
  int hazardous_impacts() const { return hazardous_total_; }
  const std::vector<std::uint64_t>& plane_crossings() const { return plane_crossings_; }
  const std::vector<std::uint64_t>& plane_hazards() const { return plane_hazards_; }

 private:
  Vec3 ground(double t, const Vec3& p) const { return p + Vec3(ground_speed_ * (t - strike_time_), 0, 0); }
  HazardTally& tally_;
  double mass_ = 0, strike_time_ = 0, ground_speed_ = 0;
  bool watching_ = false;  // thrown() was called for the object under way
  bool landed_ = false;
  double farthest_ = -1;
  static constexpr int kMaxImpacts = 256;
  std::array<std::array<double, 2>, kMaxImpacts> impacts_{};  // hazardous ground impacts, ground frame
  int impact_count_ = 0;
  std::array<int, kMaxImpacts> side_crossings_{};  // hazardous crossings of the side planes: side * half_cells + bin
  int side_crossing_count_ = 0;
  std::vector<std::uint64_t> plane_hazards_, plane_crossings_;  // this object's, per plane
  int hazardous_total_ = 0;
};

// What one chunk of a parallel run fills (field::run_hazard, field::compare_fields): a tally
// per kind of object (per design and kind in a comparison), each with its watch.
struct WatchedTallies {
  std::deque<HazardTally> tallies;  // a deque: each watch keeps its tally's address
  std::deque<ObjectWatch> watches;
  void add(const HazardLayout& layout) { tallies.emplace_back(layout), watches.emplace_back(tallies.back()); }
  void clear() {
    for (auto& t : tallies) t.clear();
  }
  // Every tally's counts appended to a message, and read back from `at` on.
  void pack_at(std::string& out) const {
    for (const auto& t : tallies) t.pack_at(out);
  }
  void unpack_at(const std::string& bytes, std::size_t& at) {
    for (auto& t : tallies) t.unpack_at(bytes, at);
  }
};

}  // namespace j232::field
