#include "field/hazard_run.hpp"

#include "assess/bytes.hpp"
#include "assess/chunk_runner.hpp"
#include "assess/cluster.hpp"
#include "assess/summary.hpp"
#include "invariant/check.hpp"

#include <algorithm>
#include <array>
#include <boost/math/special_functions/gamma.hpp>
#include <chrono>
#include <cmath>
#include <deque>
#include <fmt/format.h>
#include <stdexcept>

namespace j232::field {

std::uint64_t HazardRun::objects() const {
  std::uint64_t n = 0;
  for (const auto& t : strata) n += t.objects;
  return n;
}

std::uint64_t slots_per_wave(std::size_t bytes_per_slot, int threads) {
  constexpr std::size_t kBudget = std::size_t{512} << 20;
  const auto per_thread = static_cast<std::uint64_t>(std::max(threads, 1));
  const std::uint64_t fit = kBudget / std::max<std::size_t>(bytes_per_slot, 1);
  return std::clamp<std::uint64_t>(fit, per_thread, 8 * per_thread);
}

HazardRun empty_run(const FieldSimulator& sim) {
  const HazardLayout layout = HazardLayout::of(sim.scenario().field);
  HazardRun run;
  for (std::size_t k = 0; k < sim.strata(); ++k) run.strata.emplace_back(layout);
  return run;
}

void run_hazard_objects(const FieldSimulator& sim, std::uint64_t objects, std::uint64_t first, std::uint64_t count, HazardRun& run,
                        int threads, assess::Progress* progress, const ObjectRows* rows) {
  const HazardLayout layout = HazardLayout::of(sim.scenario().field);
  const std::size_t strata_count = sim.strata();
  const std::uint64_t per_chunk = objects_per_chunk(objects), end = first + count;
  J232_CHECK(run.strata.size() == strata_count && first % per_chunk == 0 && end <= objects);
  // One runner for every pipeline (assess/chunk_runner.hpp): chunks of objects, each into a
  // slot's tallies (and its objects' rows for a comparison), merged in chunk order (whole
  // counts: any order would give the same sums; the rows go to the sink in object order).
  struct Slot {
    WatchedTallies watched;
    std::vector<double> rows;  // the chunk's objects' rows, rows->width each
  };
  const std::size_t width = rows ? rows->width : 0;
  std::deque<Slot> slots;
  assess::ChunkWork work;
  work.chunks = (count + per_chunk - 1) / per_chunk;
  work.most_slots = slots_per_wave(strata_count * run.strata.front().bytes(), assess::thread_count(threads));
  work.items = [&](std::uint64_t chunk) { return std::min(end, first + (chunk + 1) * per_chunk) - (first + chunk * per_chunk); };
  work.run = [&](std::uint64_t chunk, std::size_t slot) {
    Slot& s = slots[slot];
    s.watched.clear();
    const std::uint64_t from = first + chunk * per_chunk, last = std::min(end, from + per_chunk);
    s.rows.assign(static_cast<std::size_t>(last - from) * width, 0.0);
    for (std::uint64_t i = from; i < last; ++i) {
      ObjectWatch& watch = s.watched.watches[static_cast<std::size_t>(i % strata_count)];
      const ObjectOutcome o = sim.simulate(i, &watch);
      watch.finish(o);
      if (rows) rows->count(o, watch, &s.rows[static_cast<std::size_t>(i - from) * width]);
    }
  };
  work.merge = [&](std::uint64_t chunk, std::size_t slot) {
    const Slot& s = slots[slot];
    for (std::size_t k = 0; k < strata_count; ++k) run.strata[k].merge(s.watched.tallies[k]);
    if (rows && rows->sink)
      for (std::size_t i = 0; i * width < s.rows.size(); ++i) rows->sink(first + chunk * per_chunk + i, &s.rows[i * width]);
  };
  work.pack = [&](std::size_t n) {
    assess::ByteWriter w;
    for (std::size_t i = 0; i < n; ++i) w.list(slots[i].rows, slots[i].rows.size());
    std::string bytes = w.take();
    for (std::size_t i = 0; i < n; ++i) slots[i].watched.pack_at(bytes);
    return bytes;
  };
  work.unpack = [&](const std::string& bytes, std::size_t n) {
    assess::ByteReader r(bytes);
    for (std::size_t i = 0; i < n; ++i) r.list(slots[i].rows);
    std::size_t at = r.position();
    for (std::size_t i = 0; i < n; ++i) slots[i].watched.unpack_at(bytes, at);
    if (at != bytes.size()) throw std::runtime_error("hazard tallies: bytes of another layout from another rank");
  };
  work.progress = progress;
  slots.resize(static_cast<std::size_t>(assess::wave_size(work)));
  for (auto& slot : slots)
    for (std::size_t k = 0; k < strata_count; ++k) slot.watched.add(layout);
  run.threads = assess::on_threads(threads, [&] { assess::run_chunks(work); });
}

HazardRun run_hazard(const FieldSimulator& sim, int threads, assess::Progress* progress, const ObjectRows* rows) {
  const auto n = static_cast<std::uint64_t>(sim.scenario().field.objects_simulated);
  HazardRun run = empty_run(sim);
  if (progress) progress->total = static_cast<long long>(n);
  const auto start = std::chrono::steady_clock::now();
  run_hazard_objects(sim, n, 0, n, run, threads, progress, rows);
  if (assess::cluster::size() > 1) {
    // Every rank goes on from the whole run, as after a J232 assessment's.
    std::string whole;
    if (assess::cluster::is_writer())
      for (const auto& t : run.strata) t.pack_at(whole);
    assess::cluster::broadcast_from_writer(whole);
    if (!assess::cluster::is_writer()) {
      std::size_t at = 0;
      for (auto& t : run.strata) t.unpack_at(whole, at);
      if (at != whole.size()) throw std::runtime_error("hazard tallies: bytes of another layout from rank 0");
    }
  }
  run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

double heaviest_weight(const std::vector<Stratum>& strata) {
  double largest = 0;
  for (const auto& s : strata)
    // (A stratum that made the event can make it, whatever its energy bound says.)
    if (s.possible || s.counts.sum > 0) largest = std::max(largest, s.weight_per_object);
  return largest;
}

Estimate combined(const std::vector<Stratum>& strata) {
  double mean = 0, variance = 0;
  for (const auto& s : strata) {
    mean += s.weight_per_object * static_cast<double>(s.counts.sum);
    variance += s.weight_per_object * s.weight_per_object * static_cast<double>(s.counts.squares);
  }
  Estimate e = quasi_poisson(mean, variance, heaviest_weight(strata));
  e.variance = variance;
  return e;
}

Estimate quasi_poisson(double mean, double variance, double heaviest) {
  // Fay and Feuer's gamma interval for a weighted sum of Poisson counts (Statistics in
  // Medicine 16, 1997): the lower end from a gamma of the estimate's mean and variance, the
  // upper from one that adds an event of the heaviest weight, so that a stratum that saw
  // nothing still widens it. With equal weights it is Garwood's exact Poisson interval.
  const double w = heaviest;
  const double high_shape = (mean + w) * (mean + w) / (variance + w * w), high_scale = (variance + w * w) / (mean + w);
  const double high = w > 0 || mean > 0 ? boost::math::gamma_p_inv(high_shape, 0.975) * high_scale : 0.0;
  if (!(mean > 0) || !(variance > 0)) return {0.0, 0.0, high};
  const double scale = variance / mean, effective = mean / scale;
  return {mean, boost::math::gamma_p_inv(effective, 0.025) * scale, high};
}

std::vector<double> weights_per_object(const FieldSimulator& sim, const HazardRun& run) { return weights_per_object(sim, run.objects()); }

std::vector<double> weights_per_object(const FieldSimulator& sim, std::uint64_t objects) {
  std::vector<double> w;
  const std::size_t strata_count = sim.strata();
  for (std::size_t k = 0; k < strata_count; ++k) {
    const double n = static_cast<double>(objects / strata_count + (k < objects % strata_count ? 1 : 0));
    const FieldSimulator::SizeStratum& s = sim.stratum(k);
    w.push_back(n > 0 ? sim.objects_per_metre(s.kind) * s.share / n : 0.0);
  }
  return w;
}

namespace {

Estimate struck(const Estimate& density, double area) {
  auto p = [&](double q) { return -std::expm1(-q * area); };
  // Its noise to first order: dP/dq = A exp(-q A).
  const double slope = area * std::exp(-density.value * area);
  return {p(density.value), p(density.low), p(density.high), slope * slope * density.variance};
}

// Where a curve falls below `acceptable` for good: the outer edge of the last cell at or
// above it (none beyond the deck: the deck's edge).
void hazard_distance(double cell, double acceptable, DirectionCurve& c) {
  auto last_at_or_above = [&](auto value) {
    int last = -1;
    for (std::size_t k = 0; k < c.exposure.size(); ++k)
      if (value(c.exposure[k]) >= acceptable) last = static_cast<int>(k);
    return last;
  };
  const bool beside = c.direction == "left" || c.direction == "right";  // a strip's distance is its middle
  auto outer_edge = [&](int k) { return k < 0 ? c.deck_extent : c.distance[static_cast<std::size_t>(k)] + (beside ? 0.5 : 1.0) * cell; };
  const int est = last_at_or_above([](const Estimate& e) { return e.value; });
  const int up = last_at_or_above([](const Estimate& e) { return e.high; });
  c.hazard_distance = outer_edge(est);
  c.hazard_distance_upper = outer_edge(up);
  c.beyond_range = est >= 0 && est + 1 == static_cast<int>(c.exposure.size());
  c.upper_beyond_range = up >= 0 && up + 1 == static_cast<int>(c.exposure.size());
}

}  // namespace

namespace {

// What the run counted (objects, thrown, cut off, landed outside the deck) and whether it
// may claim a hazard: no object thrown, or more than kMaxCutOffShare cut off by the run's
// limits, and it may not (named, so the user knows which setting to raise).
void count_and_judge(const FieldSimulator& sim, const HazardRun& run, const std::vector<double>& w, HazardSummary& s) {
  const std::size_t strata_count = run.strata.size();
  s.objects = run.objects();
  double thrown = 0, landed = 0, thrown_variance = 0;
  for (std::size_t k = 0; k < strata_count; ++k) {
    const HazardTally& t = run.strata[k];
    const std::uint64_t thrown_k = t.fates[static_cast<std::size_t>(ObjectFate::Thrown)] + t.fates[static_cast<std::size_t>(ObjectFate::CutOff)];
    s.thrown += thrown_k;
    s.cut_off += t.fates[static_cast<std::size_t>(ObjectFate::CutOff)];
    s.max_distance = std::max(s.max_distance, t.max_distance);
    thrown += w[k] * static_cast<double>(thrown_k);
    if (t.objects > 0) {
      const double n = static_cast<double>(t.objects), share = static_cast<double>(thrown_k) / n;
      thrown_variance += w[k] * w[k] * n * share * (1 - share);
    }
    std::uint64_t landed_k = t.landed_beyond_square;
    for (auto c : t.landings) landed_k += c;
    landed += w[k] * static_cast<double>(landed_k);
  }
  s.cut_off_share = s.objects ? static_cast<double>(s.cut_off) / static_cast<double>(s.objects) : 0.0;
  {
    // Which limits cut them off, so the user knows which setting to raise.
    std::array<std::uint64_t, flight::kCutOffReasons> by{};
    for (const auto& t : run.strata)
      for (std::size_t i = 0; i < by.size(); ++i) by[i] += t.cut_off_by[i];
    for (int i = 1; i < flight::kCutOffReasons; ++i)
      if (by[static_cast<std::size_t>(i)])
        s.cut_off_limits += fmt::format("{}{} by {}", s.cut_off_limits.empty() ? "" : ", ", by[static_cast<std::size_t>(i)],
                                        flight::cut_off_setting(static_cast<flight::CutOff>(i)));
  }
  if (s.objects == 0 || s.thrown == 0) {
    s.valid = false;
    s.invalid_reason = "no object was thrown: the blades reached none of the field's objects, so there is no hazard to assess";
  } else if (s.cut_off_share > assess::kMaxCutOffShare) {
    // (The J232 test's limits, with every object simulated as the denominator: each one lies
    // where a blade can reach it, as each nail of the test is fed to the blade.)
    s.valid = false;
    s.invalid_reason = fmt::format("{:.2f} % of the objects were cut off still moving by the run's limits (more than {:g} %): {}",
                                   100 * s.cut_off_share, 100 * assess::kMaxCutOffShare, s.cut_off_limits);
  }
  s.warnings = sim.scenario().notes;
  if (s.valid && s.cut_off_share >= assess::kWarnCutOffShare)
    s.warnings.push_back(fmt::format("{:.2f} % of the objects were cut off still moving (a run withholds its answer from {:g} %): {}",
                                     100 * s.cut_off_share, 100 * assess::kMaxCutOffShare, s.cut_off_limits));
  s.thrown_per_km = 1000 * thrown;
  s.thrown_per_km_variance = 1e6 * thrown_variance;
  s.landed_outside_deck_share = thrown > 0 ? landed / thrown : 0.0;
}

// Throw statistics over the strata, each weighted as the field holds it: the speed off the
// first and the last strike (mean, 95th percentile) and the launch's elevation.
void throw_statistics(const HazardRun& run, const std::vector<double>& w, HazardSummary& s) {
  const std::size_t strata_count = run.strata.size();
  // A speed histogram's (0.5 m/s bins) mean and 95th percentile over the strata.
  const auto mean_and_q95 = [&](std::array<std::uint64_t, 400> HazardTally::*histogram, double& mean, double& q95) {
    double n = 0, sum = 0;
    std::vector<double> speed((run.strata.front().*histogram).size());
    for (std::size_t k = 0; k < strata_count; ++k)
      for (std::size_t i = 0; i < speed.size(); ++i) {
        const double c = w[k] * static_cast<double>((run.strata[k].*histogram)[i]);
        speed[i] += c, n += c, sum += c * (static_cast<double>(i) + 0.5) * 0.5;
      }
    mean = n > 0 ? sum / n : 0.0;
    double seen = 0;
    for (std::size_t i = 0; i < speed.size(); ++i) {
      seen += speed[i];
      if (n > 0 && seen >= 0.95 * n) {
        q95 = (static_cast<double>(i) + 1) * 0.5;
        break;
      }
    }
  };
  mean_and_q95(&HazardTally::exit_speed, s.exit_speed_mean, s.exit_speed_q95);
  mean_and_q95(&HazardTally::last_strike_speed, s.last_strike_speed_mean, s.last_strike_speed_q95);
  double elevation = 0, en = 0;
  for (std::size_t k = 0; k < strata_count; ++k)
    for (std::size_t i = 0; i < run.strata[k].launch_elevation.size(); ++i) {
      const double c = w[k] * static_cast<double>(run.strata[k].launch_elevation[i]);
      en += c, elevation += c * (static_cast<double>(i) + 0.5 - 90.0);
    }
  s.launch_elevation_mean = en > 0 ? elevation / en : 0.0;
}

// Each direction's curve from the deck's edge outward (the density of hazardous impacts,
// beside the path the crossings of the vertical plane too, the exposure and P(struck)), and
// its hazard distance at the acceptable density and at each setback factor of it.
void direction_curves(const FieldSimulator& sim, const HazardRun& run, const std::vector<double>& w, HazardSummary& s) {
  const scenario::FieldSpec& f = sim.scenario().field;
  const HazardLayout& l = run.strata.front().layout;
  const std::size_t strata_count = run.strata.size();
  static const char* names[] = {"left", "right", "front", "rear"};
  static const char* meanings[] = {
      "a person standing this far to the left of the mower's centre line while it mows past (one pass): the larger of the "
      "hazardous impacts per m2 of ground there and the hazardous crossings per m2 of the vertical plane there",
      "a person standing this far to the right of the mower's centre line while it mows past (one pass): the larger of the "
      "hazardous impacts per m2 of ground there and the hazardous crossings per m2 of the vertical plane there",
      "a person on the mower's line ahead of it, whom it approaches to no nearer than this",
      "a person on the mower's line behind it, from whom it moves away from this distance on"};
  std::vector<Stratum> strata(strata_count);
  // How far the deck reaches in each direction: nobody stands under it, so each curve starts
  // at the first cell wholly beyond it.
  std::array<double, 4> deck_extent{};
  for (const auto& p : sim.mower().footprint().outline)
    deck_extent = {std::max(deck_extent[0], p.y()), std::max(deck_extent[1], -p.y()), std::max(deck_extent[2], p.x()),
                   std::max(deck_extent[3], -p.x())};
  for (std::size_t d = 0; d < 4; ++d) {
    DirectionCurve c;
    c.direction = names[d], c.meaning = meanings[d];
    c.deck_extent = deck_extent[d];
    // Beside the path: impacts in a strip one cell wide along the whole pass; on the line:
    // in a band one cell wide, summed over the distances the mower passes through.
    for (int k = static_cast<int>(std::ceil(deck_extent[d] / l.cell - 1e-9)); k < l.half_cells; ++k) {
      c.distance.push_back(d < 2 ? (k + 0.5) * l.cell : k * l.cell);
      for (std::size_t j = 0; j < strata_count; ++j)
        strata[j] = {run.strata[j].directions[d][static_cast<std::size_t>(k)], w[j], sim.stratum(j).energy_bound >= f.person_energy};
      const Estimate q = combined(strata).scaled(1.0 / l.cell);
      c.density.push_back(q);
      Estimate exposure = q;
      if (d < 2) {
        // The plane along the path there: crossings per metre travelled over the person's height.
        for (std::size_t j = 0; j < strata_count; ++j)
          strata[j] = {run.strata[j].vertical[d][static_cast<std::size_t>(k)], w[j], sim.stratum(j).energy_bound >= f.person_energy};
        const Estimate v = combined(strata).scaled(1.0 / f.person_height);
        c.vertical.push_back(v);
        exposure = {std::max(q.value, v.value), std::max(q.low, v.low), std::max(q.high, v.high)};
      }
      c.exposure.push_back(exposure);
      c.probability.push_back(struck(exposure, f.presented_area));
    }
    for (double factor : kSetbackFactors) {
      DirectionCurve at = c;
      hazard_distance(l.cell, factor * s.acceptable_density, at);
      c.setbacks.push_back({factor * s.acceptable_density, at.hazard_distance, at.hazard_distance_upper, at.beyond_range, at.upper_beyond_range});
    }
    hazard_distance(l.cell, s.acceptable_density, c);
    s.directions.push_back(std::move(c));
  }
}

// Each plane's crossings per km by height, its hazardous crossings per km, and beside the
// path, per m2 of it, with P(struck) per pass and per season for a person there.
void plane_results(const FieldSimulator& sim, const HazardRun& run, const std::vector<double>& w, HazardSummary& s) {
  const scenario::FieldSpec& f = sim.scenario().field;
  const std::size_t strata_count = run.strata.size();
  std::vector<Stratum> strata(strata_count);
  for (std::size_t p = 0; p < f.planes.size(); ++p) {
    PlaneResult r;
    r.plane = f.planes[p];
    r.per_km_by_height.assign(kHeightBands, 0.0);
    for (std::size_t j = 0; j < strata_count; ++j) {
      const PlaneTally& pt = run.strata[j].planes[p];
      for (int b = 0; b < kHeightBands; ++b) {
        const double c = 1000 * w[j] * static_cast<double>(pt.by_height[static_cast<std::size_t>(b)]);
        r.per_km_by_height[static_cast<std::size_t>(b)] += c;
        r.crossings_per_km += c;
      }
      const double threshold = r.plane.receptor == scenario::FieldPlaneSpec::Receptor::Person ? f.person_energy : f.vehicle_energy;
      strata[j] = {pt.hazardous, w[j], sim.stratum(j).energy_bound >= threshold};
    }
    const Estimate rate = combined(strata);  // per metre travelled
    r.hazardous_per_km = rate.scaled(1000);
    const bool person = r.plane.receptor == scenario::FieldPlaneSpec::Receptor::Person;
    const double band = person ? f.person_height : f.windshield_top - f.windshield_bottom;
    // Beside the path, the plane runs along the whole pass: a rate per metre travelled is a
    // flux per metre of the plane's length. Ahead or behind it stands across the path, d from
    // the mower at each strike: per km only.
    r.along_path = r.plane.side == scenario::FieldPlaneSpec::Side::Left || r.plane.side == scenario::FieldPlaneSpec::Side::Right;
    if (r.along_path) {
      r.hazardous_per_area = rate.scaled(1.0 / band);
      if (person) {
        r.probability = struck(r.hazardous_per_area, f.presented_area);
        // Passes are independent draws of the same field: at least once in n passes.
        const double n = static_cast<double>(f.passes_per_season);
        const auto season = [&](double p1) { return -std::expm1(n * std::log1p(-p1)); };
        r.probability_per_season = {season(r.probability.value), season(r.probability.low), season(r.probability.high)};
        r.people_struck_per_season = r.probability.scaled(n * f.people_per_pass);
      }
    }
    s.planes.push_back(std::move(r));
  }
}

}  // namespace

HazardTally kind_tally(const FieldSimulator& sim, const HazardRun& run, std::size_t kind) {
  HazardTally t(run.strata.front().layout);
  for (std::size_t k = 0; k < run.strata.size(); ++k)
    if (sim.stratum(k).kind == kind) t.merge(run.strata[k]);
  return t;
}

HazardSummary summarise(const FieldSimulator& sim, const HazardRun& run) {
  const scenario::FieldSpec& f = sim.scenario().field;
  const std::vector<double> w = weights_per_object(sim, run);
  HazardSummary s;
  s.cut_width = sim.cut_to() - sim.cut_from();
  s.objects_per_metre = sim.objects_per_metre();
  s.objects_per_km = 1000 * s.objects_per_metre;
  for (std::size_t k = 0; k < sim.kinds(); ++k) s.reaching_per_km += 1000 * sim.objects_per_metre(k) * sim.reach_share(k);
  s.acceptable_density = 1.0 / f.acceptable_area;
  count_and_judge(sim, run, w, s);
  throw_statistics(run, w, s);
  direction_curves(sim, run, w, s);
  plane_results(sim, run, w, s);
  return s;
}

}  // namespace j232::field
