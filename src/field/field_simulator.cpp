#include "field/field_simulator.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "scenario/input_error.hpp"
#include "strike/contact_search.hpp"
#include "flight/launch.hpp"
#include "flight/plane_touch.hpp"
#include "invariant/check.hpp"
#include "strike/impulse.hpp"
#include "units/quantity.hpp"

namespace j232::field {

const char* object_fate_name(ObjectFate f) {
  switch (f) {
    case ObjectFate::NotReached: return "not_reached";
    case ObjectFate::NotThrown: return "not_thrown";
    case ObjectFate::Thrown: return "thrown";
    case ObjectFate::CutOff: return "cut_off";
  }
  return "unknown";
}

namespace {

const scenario::Scenario& with_field(const scenario::Scenario& s) {
  if (!s.field.present)
    throw scenario::InputError(s.file, std::nullopt, "field", "",
                               "missing: j232 hazard needs a [field] table (the objects the mower meets); a scenario without it is "
                               "the J232 test (j232 run)");
  return s;
}

// The size of an object at probability p of its kind's lognormal (geometric spread 1:
// one size).
double size_at(const scenario::FieldObjectSpec& o, double p) {
  if (o.spread <= 1.0) return o.median_size;
  const boost::math::normal_distribution<double> z;
  return std::clamp(o.median_size * std::exp(std::log(o.spread) * boost::math::quantile(z, std::clamp(p, 1e-300, 1 - 1e-16))), o.min_size,
                    o.max_size);
}
// The lognormal's probability of sizes below d.
double probability_below(const scenario::FieldObjectSpec& o, double d) {
  if (o.spread <= 1.0) return d > o.median_size ? 1.0 : 0.0;
  return boost::math::cdf(boost::math::normal_distribution<double>(), std::log(d / o.median_size) / std::log(o.spread));
}

}  // namespace

FieldSimulator::FieldSimulator(const scenario::Scenario& s, scene::Engine engine) : scenario_(with_field(s)) {
  mower_ = std::make_unique<flight::Mower>(scenario_, engine);
  cut_from_ = HUGE_VAL, cut_to_ = -HUGE_VAL;
  for (const auto& sp : scenario_.spindles) {
    cut_from_ = std::min(cut_from_, sp.y - sp.blade.tip_radius());
    cut_to_ = std::max(cut_to_, sp.y + sp.blade.tip_radius());
  }
  for (std::size_t k = 0; k < scenario_.field.objects.size(); ++k) {
    const auto& o = scenario_.field.objects[k];
    std::vector<strike::Spindle> spindles =
        strike::scenario_spindles(scenario_, o.restitution ? blade::Restitution::constant(*o.restitution) : scenario_.restitution);
    for (auto& sp : spindles) sp.friction = o.friction;
    spindles_.push_back(std::move(spindles));
    // A sphere's drag: rho C_d (pi d^2 / 4) / (2 m) with m = rho_s pi d^3 / 6, that is
    // 3 rho C_d / (4 rho_s d): worked out here for d = 1 m.
    flight::Drag drag;
    drag.on = scenario_.air.drag;
    drag.k_axial = drag.k_normal = 3 * scenario_.air.density * o.drag_coefficient / (4 * o.density);
    drag.sphere = true;
    drag.k_spin = 0;  // a sphere's spin does not change its drag (no Magnus lift modelled)
    drag.air = {-scenario_.field.ground_speed, 0.0, 0.0};  // still air, seen from the moving mower
    drag.spin_average = scenario_.air.spin_average;
    drag_per_unit_.push_back(drag);
    // The sizes that can reach a blade: lifted by the updraft (drag above weight: below
    // 3 rho C_d u^2 / (4 rho_s g)), or standing above the lowest blade's lower face (with
    // support, some of every size stand so: held_up).
    const double u = scenario_.field.updraft_speed;
    const double lifted_below = scenario_.lifted_up_to(o, o.drag_coefficient, u);
    const double tall_above = scenario_.lowest_blade_face() / (1 - o.embedment);
    ReachableSizes reach;
    const double lo = probability_below(o, o.min_size), hi = o.spread <= 1.0 ? 1.0 : probability_below(o, o.max_size);
    const double whole = o.spread <= 1.0 ? 1.0 : hi - lo;
    // Sizes that reach for certain, [from, to) on the p axis: cells of reach 1, fine enough
    // for the size strata to split them.
    const auto certain = [&](double from, double to) {
      constexpr int kCells = 32;
      for (int i = 0; i < kCells; ++i) {
        const double a = from + (to - from) * i / kCells, b = from + (to - from) * (i + 1) / kCells;
        reach.cells.push_back({a, b, b - a, 1.0, true});
      }
    };
    if (scenario_.field.support_height > 0) {
      // The lifted sizes [lo, lifted_at); above them, each size reaches with the probability
      // its support holds it in the band.
      const double lifted_at = std::clamp(o.spread <= 1.0 ? (o.median_size < lifted_below ? 1.0 : 0.0)
                                                          : probability_below(o, std::max(lifted_below, o.min_size)),
                                          lo, hi);
      if (lifted_at > lo) certain(lo, lifted_at);
      if (hi > lifted_at) {
        // A grid over [lifted_at, hi] with a node where the object's top on the plane meets
        // the blade's face: on each cell the reach probability is then monotone in p (rising
        // below that size, falling above it as the front's gap closes), so the larger of a
        // cell's ends bounds it there.
        constexpr int kCells = 1024;
        std::vector<double> grid;
        for (int i = 0; i <= kCells; ++i) grid.push_back(lifted_at + (hi - lifted_at) * i / kCells);
        if (o.spread > 1.0 && tall_above > o.min_size && tall_above < o.max_size) {
          const double peak = probability_below(o, tall_above);
          if (peak > lifted_at && peak < hi) grid.insert(std::upper_bound(grid.begin(), grid.end(), peak), peak);
        }
        const auto w = [&](double p) { return held_up(k, size_at(o, p)).probability; };
        double left = w(grid.front());
        for (std::size_t i = 0; i + 1 < grid.size(); ++i) {
          const double a = grid[i], b = grid[i + 1], right = w(b);
          const double mass = (b - a) * (left + 4 * w(0.5 * (a + b)) + right) / 6;  // Simpson's rule
          if (std::max(left, right) > 0) reach.cells.push_back({a, b, mass, std::max(left, right), false});
          left = right;
        }
      }
    } else {
      // Standing up to the blade, and low enough to pass under the deck's front (the reader
      // refuses a file whose largest does not; a sweep's cut_height can lower the deck).
      std::vector<std::array<double, 2>> pieces;
      auto add = [&](double from, double to) {  // sizes [from, to) within the cut
        from = std::max(from, o.min_size), to = std::min(to, o.max_size);
        if (o.spread <= 1.0) {
          if (o.median_size >= from && o.median_size <= to) pieces.push_back({0.0, 1.0});
          return;
        }
        if (!(to > from)) return;
        const double a = probability_below(o, from), b = probability_below(o, to);
        if (!pieces.empty() && a <= pieces.back()[1])
          pieces.back()[1] = std::max(pieces.back()[1], b);
        else if (b > a)
          pieces.push_back({a, b});
      };
      const std::optional<double> front_gap = scenario_.front_gap();
      add(0.0, lifted_below);
      add(tall_above, front_gap ? *front_gap / (1 - o.embedment) : HUGE_VAL);
      if (pieces.size() == 2 && pieces[1][0] <= pieces[0][1]) {
        pieces[0][1] = std::max(pieces[0][1], pieces[1][1]);
        pieces.pop_back();
      }
      for (const auto& piece : pieces) certain(piece[0], piece[1]);
    }
    reach.cumulative.push_back(0);
    double mass = 0;
    for (const auto& c : reach.cells) {
      reach.cumulative.push_back(reach.cumulative.back() + (c.to - c.from) * c.envelope);
      mass += c.mass;
    }
    reach.share = std::min(1.0, mass / whole);
    if (!(reach.share > 0))
      throw scenario::InputError(scenario_.file, std::nullopt, fmt::format("field.objects[{}]", k + 1), "",
                                 "no size of these objects can reach a blade (none stands up to a blade's lower face, none is light "
                                 "enough for the updraft): expected larger objects, less embedment, a lower cut or an updraft");
    add_size_strata(k, whole, reach);
    sizes_.push_back(reach);
  }
  if (scenario_.field.objects_simulated < static_cast<long long>(strata_.size()))
    throw scenario::InputError(scenario_.file, std::nullopt, "field.objects_simulated", std::to_string(scenario_.field.objects_simulated),
                               fmt::format("at least one object of each of the {} strata the {} kinds are drawn from (each kind's sizes "
                                           "in up to {} size strata)",
                                           strata_.size(), scenario_.field.objects.size(), kSizeStrata));
}

FieldSimulator::SupportBand FieldSimulator::held_up(std::size_t kind, double size) const {
  const auto& o = scenario_.field.objects[kind];
  const double mean = scenario_.field.support_height, top = size * (1 - o.embedment);
  const std::optional<double> front_gap = scenario_.front_gap();
  SupportBand band;
  band.from = std::max(0.0, scenario_.lowest_blade_face() - top);
  band.to = front_gap ? *front_gap - top : HUGE_VAL;
  if (!(band.to > band.from)) return band;
  if (scenario_.field.support_shape == scenario::FieldSpec::SupportShape::HalfNormal) {
    // Half-normal heights of this mean (sigma = mean sqrt(pi/2)): P(b > x) = erfc(x / (sigma sqrt 2)).
    const double scale = mean * std::sqrt(units::pi);  // sigma sqrt 2
    band.probability = std::erfc(band.from / scale) - (band.to < HUGE_VAL ? std::erfc(band.to / scale) : 0.0);
    return band;
  }
  // Exponential heights of this mean: P(from < b < to) = exp(-from / mean) - exp(-to / mean).
  band.probability = std::exp(-band.from / mean) - (band.to < HUGE_VAL ? std::exp(-band.to / mean) : 0.0);
  return band;
}

double FieldSimulator::objects_per_metre(std::size_t kind) const { return scenario_.field.objects[kind].per_area * met_width(kind); }

double FieldSimulator::objects_per_metre() const {
  double sum = 0;
  for (std::size_t k = 0; k < kinds(); ++k) sum += objects_per_metre(k);
  return sum;
}

// A kind's reachable sizes split into strata of about equal shares of their mass (the
// cells' reach mass times the cube of their size), so that the few heavy objects that carry a
// hazardous energy are drawn as often as the many light ones; a kind of one size has one.
void FieldSimulator::add_size_strata(std::size_t kind, double whole, const ReachableSizes& reach) {
  const auto& o = scenario_.field.objects[kind];
  const std::size_t n = reach.cells.size();
  const std::size_t bands = o.spread <= 1.0 ? 1 : std::min<std::size_t>(kSizeStrata, n);
  std::vector<double> heavy(n + 1, 0.0);  // the cells' mass-weighted reach, cumulative
  for (std::size_t c = 0; c < n; ++c) {
    const double d = size_at(o, 0.5 * (reach.cells[c].from + reach.cells[c].to));
    heavy[c + 1] = heavy[c] + reach.cells[c].mass * d * d * d;
  }
  std::size_t first = 0;
  for (std::size_t b = 1; b <= bands && first < n; ++b) {
    std::size_t end = n;
    if (b < bands) {
      const double target = heavy[n] * static_cast<double>(b) / static_cast<double>(bands);
      end = first + 1;
      while (end < n - (bands - b) && heavy[end] < target) ++end;
    }
    double mass = 0;
    for (std::size_t c = first; c < end; ++c) mass += reach.cells[c].mass;
    if (mass > 0 || strata_.empty() || strata_.back().kind != kind) {
      SizeStratum s;
      s.kind = kind, s.first_cell = first, s.end_cell = end, s.share = mass / whole;
      strata_.push_back(s);
    } else {
      strata_.back().end_cell = end;  // (a stratum that reaches nothing joins the one below)
    }
    first = end;
  }
  // Each stratum's sizes, and a bound on the kinetic energy any of them can have after the
  // blades threw it: its largest at (1 + e) <= 2 times the fastest tip speed with a margin,
  // plus the mower's travel and a fall of 5 m.
  for (auto& s : strata_) {
    if (s.kind != kind) continue;
    s.smallest = size_at(o, reach.cells[s.first_cell].from), s.largest = size_at(o, reach.cells[s.end_cell - 1].to);
    const double m = o.density * units::pi * s.largest * s.largest * s.largest / 6;
    const double speed = 2.2 * scenario_.tip_speed() + scenario_.field.ground_speed;
    s.energy_bound = 0.5 * m * speed * speed + m * units::standard_gravity * 5.0;
  }
}

double FieldSimulator::reach_share(std::size_t kind) const {
  double share = 0;
  for (const auto& s : strata_)
    if (s.kind == kind) share += s.share;
  return std::min(1.0, share);
}

double FieldSimulator::energy_bound(std::size_t kind) const {
  double bound = 0;
  for (const auto& s : strata_)
    if (s.kind == kind) bound = std::max(bound, s.energy_bound);
  return bound;
}

// Under the envelope of the stratum's cells: a cell by its envelope's mass, p uniform in it,
// kept with the reach probability over the envelope (always, where the cell reaches for
// certain): p drawn with density proportional to its reach probability, exactly.
double FieldSimulator::drawn_size_probability(const SizeStratum& stratum, random::Stream& rng) const {
  const auto& o = scenario_.field.objects[stratum.kind];
  const ReachableSizes& reach = sizes_[stratum.kind];
  const double from = reach.cumulative[stratum.first_cell], to = reach.cumulative[stratum.end_cell];
  for (int tries = 0;; ++tries) {
    J232_CHECK(tries < 1'000'000);  // the envelope bounds a positive mass: draws are accepted
    const double m = from + rng.uniform() * (to - from);
    const auto at = std::upper_bound(reach.cumulative.begin() + static_cast<std::ptrdiff_t>(stratum.first_cell),
                                     reach.cumulative.begin() + static_cast<std::ptrdiff_t>(stratum.end_cell), m);
    const std::size_t i = std::clamp<std::size_t>(static_cast<std::size_t>(at - reach.cumulative.begin()), stratum.first_cell + 1, stratum.end_cell) - 1;
    const ReachCell& c = reach.cells[i];
    const double p = c.from + rng.uniform() * (c.to - c.from);
    if (c.certain) return p;
    if (rng.uniform() * c.envelope < held_up(stratum.kind, size_at(o, p)).probability) return p;
  }
}

Encounter FieldSimulator::sample(const SizeStratum& stratum, random::Stream& rng) const {
  Encounter e;
  e.kind = stratum.kind;
  const auto& o = scenario_.field.objects[e.kind];
  const double size = size_at(o, drawn_size_probability(stratum, rng));
  e.body = projectile::Projectile::sphere(size, o.density * units::pi * size * size * size / 6.0);
  e.lateral = cut_from_ - 0.5 * o.max_size + rng.uniform() * met_width(e.kind);
  // The updraft's drag against its weight: 1/2 rho u^2 C_d (pi d^2 / 4) > m g.
  const double u = scenario_.field.updraft_speed;
  e.lifted = u > 0 && 0.5 * scenario_.air.density * u * u * o.drag_coefficient * 0.25 * units::pi * size * size > e.body.mass * units::standard_gravity;
  if (scenario_.field.support_height > 0 && !e.lifted) {
    // Its support from the exponential cut to the band that holds it up to the blade (an
    // exponential's tail beyond `from` is `from` plus the same exponential: exact).
    const SupportBand band = held_up(e.kind, size);
    const double mean = scenario_.field.support_height;
    if (scenario_.field.support_shape == scenario::FieldSpec::SupportShape::HalfNormal) {
      // By inversion of the half-normal's tail between the band's ends.
      const double scale = mean * std::sqrt(units::pi), upper = std::erfc(band.from / scale);
      const double lower = band.to < HUGE_VAL ? std::erfc(band.to / scale) : 0.0;
      const double q = upper - rng.uniform() * (upper - lower);
      e.support = std::clamp(q > 0 ? scale * boost::math::erfc_inv(q) : band.from, band.from, band.to);
    } else {
      e.support = band.from - mean * std::log1p(rng.uniform() * std::expm1(-(band.to - band.from) / mean));
    }
  }
  e.height = e.support + 0.5 * size - o.embedment * size;  // its centre, on its support, sunk by its embedment
  return e;
}

ObjectOutcome FieldSimulator::simulate(std::uint64_t index, Watch* watch, std::vector<flight::FlightEvent>* events,
                                       std::vector<flight::FlightStretch>* stretches) const {
  const scenario::Scenario& s = scenario_;
  ObjectOutcome out;
  random::Stream rng(s.run.seed, 0, index, random::Purpose::FieldObject);
  out.encounter = sample(strata_[static_cast<std::size_t>(index % strata_.size())], rng);
  const Encounter& e = out.encounter;
  const auto& spindles = spindles_[e.kind];
  const double v = s.field.ground_speed, r = e.body.radius();
  // The blades' angles at time 0: a timed deck's locked together, the others independent.
  strike::BladePhases phases;
  const double deck_phase = units::two_pi * rng.uniform();
  for (std::size_t k = 0; k < spindles.size(); ++k)
    phases.at_zero[k] = s.spindles[k].phase ? deck_phase + *s.spindles[k].phase : units::two_pi * rng.uniform();

  // Where it enters each blade's reach (the tip circle widened by its radius), coming at
  // the mower along -x; time 0 at the first of them.
  std::array<double, strike::kMaxSpindles> entry{};
  double first_entry = -HUGE_VAL;
  for (std::size_t k = 0; k < spindles.size(); ++k) {
    const double reach = spindles[k].reach + r + 1e-3, dy = e.lateral - spindles[k].centre.y();
    entry[k] = std::abs(dy) < reach ? spindles[k].centre.x() + std::sqrt(reach * reach - dy * dy) : -HUGE_VAL;
    first_entry = std::max(first_entry, entry[k]);
  }
  if (first_entry == -HUGE_VAL) return out;  // between the blades' circles: not cut
  // The earliest touch of any blade, each searched over two of its turns from the moment
  // the object enters its reach (an arm sweeps the whole circle each turn).
  std::optional<strike::Contact> contact;
  strike::SearchStats search;
  for (std::size_t k = 0; k < spindles.size(); ++k) {
    if (entry[k] == -HUGE_VAL) continue;
    strike::Motion m;
    m.t0 = (first_entry - entry[k]) / v;
    m.p0 = {entry[k], e.lateral, e.lifted ? spindles[k].height : e.height};
    m.v0 = {-v, 0.0, 0.0};
    m.a = Vec3::Zero();  // resting on the turf as it comes (or held in the updraft)
    const double until = m.t0 + 2 * units::two_pi / spindles[k].omega();
    auto c = strike::first_contact(spindles[k], phases.at_zero[k], e.body, m, contact ? std::min(contact->time, until) : until, search,
                                   spindles[k].reference_search ? strike::SearchMethod::FixedSteps : strike::SearchMethod::Advancement);
    if (c && (!contact || c->time < contact->time)) contact = c, contact->spindle = k;
  }
  if (search.gave_up) {
    out.fate = ObjectFate::CutOff;
    out.flight.fate = flight::Fate::CutOff;
    out.flight.cut_off = flight::CutOff::SearchSteps;
    return out;
  }
  if (!contact) return out;
  const strike::Spindle& spindle = spindles[contact->spindle];
  const flight::Launch struck = flight::launch(spindle, *contact, e.body, Vec3(-v, 0.0, 0.0));
  out.fate = ObjectFate::NotThrown;
  out.spindle = contact->spindle;
  if (struck.result == flight::Launch::Result::NonFinite) {
    out.fate = ObjectFate::CutOff;
    out.flight.fate = flight::Fate::CutOff;
    out.flight.cut_off = flight::CutOff::NonFinite;
    out.flight.non_finite = true;
    return out;
  }
  if (struck.result != flight::Launch::Result::Thrown) return out;
  out.strike_time = contact->time;

  flight::Body body = struck.body;
  const strike::StrikeOutcome& hit = struck.hit;
  // Struck from above, it is driven into the soil, which takes the downward part; if the
  // blade is then still in its way, the knife rides over it (swinging back on its pivot),
  // and it leaves along the ground with what the soil's friction left it.
  // Judged on the impact alone: the driven blade's push (launch's) is for a body that no
  // soil holds, which the blade would otherwise meet again at once.
  flight::FirstContact first{contact->spindle, contact->edge};
  const flight::StruckSoil soil{r, s.ground.friction, e.support, mower_->settings().materials.ground().velocity};
  const flight::AfterStrike left = flight::after_strike(hit, spindle, *contact, body.position, &soil);
  body.velocity = left.velocity, body.spin = e.body.without_axial_spin(left.spin, body.axis);
  if (left.ride_over) {
    out.pressed = true;
    first.ridden_until = contact->time + flight::kRideOverTurn / spindle.omega();
  }
  flight::Drag drag = drag_per_unit_[e.kind];
  drag.k_axial /= e.body.diameter, drag.k_normal /= e.body.diameter;

  flight::FlightContext context = mower_->context();
  context.spindles = &spindles;
  context.events = events;
  context.stretches = stretches;
  if (watch) {
    watch->thrown(e.body.mass, contact->time);
    context.observer = watch->observer();
  }
  context.rolls = s.field.objects[e.kind].rolls;
  random::EventDraws draws(s.run.seed, 0, index);  // its flight's random events, each keyed by its number
  out.flight = flight::fly(body, e.body, drag, context, phases, first, draws);
  out.fate = out.flight.fate == flight::Fate::CutOff ? ObjectFate::CutOff : ObjectFate::Thrown;
  const Vec3 launch = out.flight.launch_velocity + Vec3(v, 0, 0);  // in the ground's frame
  out.exit_speed = launch.norm();
  out.launch_elevation = std::atan2(launch.z(), std::hypot(launch.x(), launch.y()));
  out.last_strike_speed = (out.flight.trace.last_strike_velocity + Vec3(v, 0, 0)).norm();
  return out;
}

}  // namespace j232::field
