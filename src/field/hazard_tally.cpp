#include "field/hazard_tally.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "invariant/check.hpp"
#include "units/quantity.hpp"

namespace j232::field {

HazardLayout HazardLayout::of(const scenario::FieldSpec& f) {
  HazardLayout l;
  l.cell = f.cell;
  l.half_cells = std::max(1, static_cast<int>(std::ceil(f.range / f.cell - 1e-9)));
  l.range = l.half_cells * l.cell;
  l.ground_speed = f.ground_speed;
  l.person_energy = f.person_energy, l.person_height = f.person_height;
  l.vehicle_energy = f.vehicle_energy, l.windshield_bottom = f.windshield_bottom, l.windshield_top = f.windshield_top;
  l.planes = f.planes;
  return l;
}

int HazardLayout::cell_of(double x, double y) const {
  const double ix = std::floor(x / cell) + half_cells, iy = std::floor(y / cell) + half_cells;
  if (!(ix >= 0 && ix < cells() && iy >= 0 && iy < cells())) return -1;
  return static_cast<int>(iy) * cells() + static_cast<int>(ix);
}

int energy_bin(double joules) {
  if (!(joules > 1e-3)) return 0;
  return std::clamp(1 + static_cast<int>(std::floor(10 * std::log10(joules / 1e-3))), 1, kEnergyBins - 1);
}
double energy_bin_low(int bin) { return bin <= 0 ? 0.0 : 1e-3 * std::pow(10.0, (bin - 1) / 10.0); }

void PlaneTally::merge(const PlaneTally& o) {
  for (std::size_t i = 0; i < by_height.size(); ++i) by_height[i] += o.by_height[i];
  for (std::size_t i = 0; i < by_energy.size(); ++i) by_energy[i] += o.by_energy[i];
  hazardous.merge(o.hazardous);
}

HazardTally::HazardTally(const HazardLayout& l)
    : layout(l),
      landings(static_cast<std::size_t>(l.cells()) * static_cast<std::size_t>(l.cells())),
      hazardous(landings.size()),
      planes(l.planes.size()) {
  for (auto& d : directions) d.resize(static_cast<std::size_t>(l.half_cells));
  for (auto& d : vertical) d.resize(static_cast<std::size_t>(l.half_cells));
}

void HazardTally::add(const ObjectOutcome& o) {
  ++objects;
  ++fates[static_cast<std::size_t>(o.fate)];
  if (o.fate == ObjectFate::CutOff) ++cut_off_by[static_cast<std::size_t>(o.flight.cut_off)];
  if (!counted_thrown(o.fate)) return;
  if (o.exit_speed > 0) {
    ++exit_speed[std::min(exit_speed.size() - 1, static_cast<std::size_t>(o.exit_speed / 0.5))];
    const double deg = std::clamp(o.launch_elevation / units::degree + 90.0, 0.0, 179.999);
    ++launch_elevation[static_cast<std::size_t>(deg)];
    ++last_strike_speed[std::min(last_strike_speed.size() - 1, static_cast<std::size_t>(o.last_strike_speed / 0.5))];
  }
  if (o.flight.fate == flight::Fate::Contained || o.flight.fate == flight::Fate::StoppedByGuard) ++at_rest_under_deck;
  if (o.pressed || o.flight.ridden_over > 0) ++ridden_over;
  if (o.flight.pushed_along > 0) ++pushed_along;
  const Eigen::Vector3d end = o.flight.end_position + Eigen::Vector3d(layout.ground_speed * o.flight.flight_time, 0, 0);
  if (std::abs(end.x()) > layout.range || std::abs(end.y()) > layout.range) ++left_square;
}

namespace {
// Adds `b` into `a`, count by count (the farthest distance: the larger).
struct Adder {
  void operator()(std::uint64_t& a, const std::uint64_t& b) const { a += b; }
  void operator()(double& a, const double& b) const { a = std::max(a, b); }
  void operator()(CountSum& a, const CountSum& b) const { a.merge(b); }
  template <class T>
  void operator()(T& a, const T& b) const {
    for (std::size_t i = 0; i < a.size(); ++i) (*this)(a[i], b[i]);
  }
};
// Sets every count to zero (the farthest distance too: its merge's identity).
struct Zeroer {
  void operator()(std::uint64_t& a, std::uint64_t&) const { a = 0; }
  void operator()(double& a, double&) const { a = 0; }
  void operator()(CountSum& a, CountSum&) const { a = {}; }
  template <class T>
  void operator()(T& a, T&) const {
    for (auto& x : a) (*this)(x, x);
  }
};
// Appends each count's bytes, or reads them back in the same order.
struct Writer {
  std::string& out;
  template <class T>
  void raw(const T& v) const { out.append(reinterpret_cast<const char*>(&v), sizeof v); }
  void operator()(const std::uint64_t& a, const std::uint64_t&) const { raw(a); }
  void operator()(const double& a, const double&) const { raw(a); }
  void operator()(const CountSum& a, const CountSum&) const { raw(a.sum), raw(a.squares); }
  template <class T>
  void operator()(const T& a, const T&) const {
    for (const auto& x : a) (*this)(x, x);
  }
};
struct Reader {
  const std::string& in;
  std::size_t& at;
  template <class T>
  void raw(T& v) const {
    if (at + sizeof v > in.size()) throw std::runtime_error("hazard tally: truncated bytes from another rank");
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
  }
  void operator()(std::uint64_t& a, std::uint64_t&) const { raw(a); }
  void operator()(double& a, double&) const { raw(a); }
  void operator()(CountSum& a, CountSum&) const { raw(a.sum), raw(a.squares); }
  template <class T>
  void operator()(T& a, T&) const {
    for (auto& x : a) (*this)(x, x);
  }
};
}  // namespace

void HazardTally::merge(const HazardTally& o) {
  // One layout: the same cells and planes (zip walks this tally's sizes through both).
  J232_CHECK(o.layout.half_cells == layout.half_cells && o.landings.size() == landings.size() && o.directions[0].size() == directions[0].size() &&
             o.vertical[0].size() == vertical[0].size() && o.planes.size() == planes.size());
  zip(*this, o, Adder{});
}

void HazardTally::clear() { zip(*this, *this, Zeroer{}); }

std::size_t HazardTally::bytes() const {
  std::size_t n = sizeof(*this);
  zip(*this, *this, [&](const auto& a, const auto&) {
    using T = std::decay_t<decltype(a)>;
    if constexpr (std::is_same_v<T, std::vector<std::uint64_t>> || std::is_same_v<T, std::vector<CountSum>>)
      n += a.size() * sizeof(typename T::value_type);
  });
  return n;
}

std::string HazardTally::pack() const {
  std::string out;
  pack_at(out);
  return out;
}

void HazardTally::pack_at(std::string& out) const { zip(*this, *this, Writer{out}); }

void HazardTally::unpack_at(const std::string& bytes, std::size_t& at) { zip(*this, *this, Reader{bytes, at}); }

void ObjectWatch::thrown(double mass, double strike_time) {
  watching_ = true;
  mass_ = mass, strike_time_ = strike_time, ground_speed_ = tally_.layout.ground_speed;
  landed_ = false, farthest_ = -1, impact_count_ = 0, hazardous_total_ = 0, side_crossing_count_ = 0;
  plane_hazards_.assign(tally_.planes.size(), 0);
  plane_crossings_.assign(tally_.planes.size(), 0);
}

namespace {
// A plane's coordinate across it and where it stands.
double across(const scenario::FieldPlaneSpec& p, const Vec3& g) {
  using Side = scenario::FieldPlaneSpec::Side;
  return p.side == Side::Left || p.side == Side::Right ? g.y() : g.x();
}
double at(const scenario::FieldPlaneSpec& p) {
  using Side = scenario::FieldPlaneSpec::Side;
  return p.side == Side::Left || p.side == Side::Front ? p.distance : -p.distance;
}
}  // namespace

void ObjectWatch::flew(double t0, const Vec3& p0, const Vec3& v0, double t1, const Vec3& p1, const Vec3& v1) {
  const HazardLayout& l = tally_.layout;
  const Vec3 g0 = ground(t0, p0), g1 = ground(t1, p1);
  // The side planes at (k + 1/2) cells it crosses, each way, below a person's height with a
  // person's hazardous energy.
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0, u0 = sign * g0.y(), u1 = sign * g1.y();
    if (u0 == u1) continue;
    const int first = std::max(0, static_cast<int>(std::ceil(std::min(u0, u1) / l.cell - 0.5)));
    const int last = std::min(l.half_cells - 1, static_cast<int>(std::floor(std::max(u0, u1) / l.cell - 0.5)));
    for (int k = first; k <= last; ++k) {
      const double f = ((k + 0.5) * l.cell - u0) / (u1 - u0);
      if (!(f > 0 && f <= 1)) continue;
      const double z = g0.z() + f * (g1.z() - g0.z());
      const double energy = 0.5 * mass_ * (v0 + f * (v1 - v0) + Vec3(ground_speed_, 0, 0)).squaredNorm();
      if (!(z <= l.person_height && energy >= l.person_energy)) continue;
      if (side_crossing_count_ < kMaxImpacts) side_crossings_[static_cast<std::size_t>(side_crossing_count_)] = side * l.half_cells + k;
      ++side_crossing_count_;
    }
  }
  for (std::size_t i = 0; i < l.planes.size(); ++i) {
    const auto& plane = l.planes[i];
    const double c0 = across(plane, g0) - at(plane), c1 = across(plane, g1) - at(plane);
    if (!((c0 < 0 && c1 >= 0) || (c0 > 0 && c1 <= 0))) continue;
    const double f = c0 / (c0 - c1);
    const double z = g0.z() + f * (g1.z() - g0.z());
    const Vec3 velocity = v0 + f * (v1 - v0) + Vec3(ground_speed_, 0, 0);
    const double energy = 0.5 * mass_ * velocity.squaredNorm();
    PlaneTally& t = tally_.planes[i];
    ++t.by_height[static_cast<std::size_t>(std::clamp(static_cast<int>(std::floor(z / kHeightBand)), 0, kHeightBands - 1))];
    ++t.by_energy[static_cast<std::size_t>(energy_bin(energy))];
    ++plane_crossings_[i];
    const bool person = plane.receptor == scenario::FieldPlaneSpec::Receptor::Person;
    const bool in_band = person ? z <= l.person_height : z >= l.windshield_bottom && z <= l.windshield_top;
    if (in_band && energy >= (person ? l.person_energy : l.vehicle_energy)) ++plane_hazards_[i];
  }
}

void ObjectWatch::met_ground(double t, const Vec3& point, const Vec3& velocity, bool in_deck) {
  if (in_deck) return;  // under the mower
  const HazardLayout& l = tally_.layout;
  const Vec3 g = ground(t, point);
  const double energy = 0.5 * mass_ * (velocity + Vec3(ground_speed_, 0, 0)).squaredNorm();
  const int cell = l.cell_of(g.x(), g.y());
  if (!landed_) {
    landed_ = true;
    if (cell >= 0)
      ++tally_.landings[static_cast<std::size_t>(cell)];
    else
      ++tally_.landed_beyond_square;
  }
  const double distance = std::hypot(g.x(), g.y());
  farthest_ = std::max(farthest_, distance);
  tally_.max_distance = std::max(tally_.max_distance, distance);
  if (!(energy >= l.person_energy)) return;
  ++hazardous_total_;
  if (cell < 0) {
    ++tally_.hazardous_beyond_square;
    return;
  }
  ++tally_.hazardous[static_cast<std::size_t>(cell)];
  if (impact_count_ < kMaxImpacts) impacts_[static_cast<std::size_t>(impact_count_)] = {g.x(), g.y()};
  ++impact_count_;
}

namespace {
// One object's events by bin (keys side * half_cells + bin, sorted here): each bin's count
// added to that side's per-object sums (its count and its square).
void add_per_bin(int* keys, int n, int half_cells, std::vector<CountSum>* sides) {
  std::sort(keys, keys + n);
  for (int i = 0; i < n;) {
    int j = i;
    while (j < n && keys[j] == keys[i]) ++j;
    sides[keys[i] / half_cells][static_cast<std::size_t>(keys[i] % half_cells)].add(static_cast<std::uint64_t>(j - i));
    i = j;
  }
}
}  // namespace

void ObjectWatch::finish(const ObjectOutcome& outcome) {
  tally_.add(outcome);
  // Only an object whose flight was watched has counts of its own (one cut off before its
  // flight, by the strike's search, has none: the last object's must not be taken for its).
  const bool thrown = watching_ && counted_thrown(outcome.fate);
  watching_ = false;
  if (!thrown || outcome.flight.fate == flight::Fate::NotStruck) {
    // Not thrown: none of its own counts (thrown() was not called for it).
    landed_ = false, hazardous_total_ = 0, impact_count_ = 0;
    plane_hazards_.assign(tally_.planes.size(), 0);
    plane_crossings_.assign(tally_.planes.size(), 0);
    return;
  }
  const HazardLayout& l = tally_.layout;
  if (farthest_ >= 0) ++tally_.farthest[std::min(tally_.farthest.size() - 1, static_cast<std::size_t>(farthest_ / 0.25))];
  if (impact_count_ > kMaxImpacts || side_crossing_count_ > kMaxImpacts) ++tally_.overflow;
  add_per_bin(side_crossings_.data(), std::min(side_crossing_count_, kMaxImpacts), l.half_cells, tally_.vertical.data());
  const int n = std::min(impact_count_, kMaxImpacts);
  // Beside the path: this object's impacts in each strip (its count and its square).
  std::array<int, kMaxImpacts> strips{};
  int strip_count = 0;
  std::array<int, 2> farthest_on_line{-1, -1};  // front, rear: the farthest bin with an impact on the line
  std::array<std::array<int, kMaxImpacts>, 2> on_line{};
  std::array<int, 2> on_line_count{0, 0};
  for (int i = 0; i < n; ++i) {
    const double x = impacts_[static_cast<std::size_t>(i)][0], y = impacts_[static_cast<std::size_t>(i)][1];
    const int side = y >= 0 ? 0 : 1;
    const int bin = static_cast<int>(std::abs(y) / l.cell);
    if (bin < l.half_cells) strips[static_cast<std::size_t>(strip_count++)] = side * l.half_cells + bin;
    if (std::abs(y) < 0.5 * l.cell) {
      const int way = x >= 0 ? 0 : 1;
      const int along = static_cast<int>(std::abs(x) / l.cell);
      if (along < l.half_cells) {
        on_line[static_cast<std::size_t>(way)][static_cast<std::size_t>(on_line_count[static_cast<std::size_t>(way)]++)] = along;
        farthest_on_line[static_cast<std::size_t>(way)] = std::max(farthest_on_line[static_cast<std::size_t>(way)], along);
      }
    }
  }
  add_per_bin(strips.data(), strip_count, l.half_cells, tally_.directions.data());
  // On the line ahead and behind: impacts at that distance or farther (a person the mower
  // comes no nearer to than that is exposed to all of them).
  for (std::size_t way = 0; way < 2; ++way) {
    for (int k = 0; k <= farthest_on_line[way]; ++k) {
      std::uint64_t beyond = 0;
      for (int i = 0; i < on_line_count[way]; ++i) beyond += on_line[way][static_cast<std::size_t>(i)] >= k ? 1 : 0;
      tally_.directions[2 + way][static_cast<std::size_t>(k)].add(beyond);
    }
  }
  for (std::size_t p = 0; p < plane_hazards_.size(); ++p) tally_.planes[p].hazardous.add(plane_hazards_[p]);
}

}  // namespace j232::field
