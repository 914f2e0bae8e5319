#include "field/field_compare.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>

#include "assess/cluster.hpp"
#include "assess/paired_runs.hpp"
#include "scenario/input_error.hpp"

namespace j232::field {

namespace {

// A figure the comparison estimates per km for each design: what it counts of a thrown
// object (a plane's, of the first design's plane `plane`), its name, and the energy its event
// needs (a stratum whose objects cannot have that energy, and made none of the events, does
// not widen its interval).
struct Figure {
  enum class Kind { Thrown, LandedOutside, HazardousImpacts, PlaneCrossings, PlaneHazards } kind = Kind::Thrown;
  std::size_t plane = 0;
  std::string name;
  double threshold = 0;  // J
};

std::vector<Figure> figures_of(const scenario::FieldSpec& fs) {
  std::vector<Figure> out = {{Figure::Kind::Thrown, 0, "objects thrown", 0.0},
                             {Figure::Kind::LandedOutside, 0, "objects first coming down outside the deck", 0.0},
                             {Figure::Kind::HazardousImpacts, 0, fmt::format("hazardous ground impacts (at least {:g} J)", fs.person_energy),
                              fs.person_energy}};
  for (std::size_t p = 0; p < fs.planes.size(); ++p) {
    const auto& plane = fs.planes[p];
    const double energy = plane.receptor == scenario::FieldPlaneSpec::Receptor::Person ? fs.person_energy : fs.vehicle_energy;
    out.push_back({Figure::Kind::PlaneCrossings, p, fmt::format("plane '{}': crossings", plane.name), 0.0});
    out.push_back({Figure::Kind::PlaneHazards, p, fmt::format("plane '{}': hazardous crossings", plane.name), energy});
  }
  return out;
}

// The figure's count for one thrown object (`plane_of`: the design's index of each of the
// first design's planes).
std::uint64_t count_of(const Figure& f, const ObjectWatch& watch, const std::vector<std::size_t>& plane_of) {
  switch (f.kind) {
    case Figure::Kind::Thrown: return 1;
    case Figure::Kind::LandedOutside: return watch.landed_outside() ? 1 : 0;
    case Figure::Kind::HazardousImpacts: return static_cast<std::uint64_t>(watch.hazardous_impacts());
    case Figure::Kind::PlaneCrossings: return watch.plane_crossings()[plane_of[f.plane]];
    case Figure::Kind::PlaneHazards: return watch.plane_hazards()[plane_of[f.plane]];
  }
  return 0;
}

// How many of the figure's events a stratum's objects made in all (from its tally).
std::uint64_t events_of(const Figure& f, const HazardTally& t, const std::vector<std::size_t>& plane_of) {
  switch (f.kind) {
    case Figure::Kind::Thrown: return t.fates[static_cast<std::size_t>(ObjectFate::Thrown)] + t.fates[static_cast<std::size_t>(ObjectFate::CutOff)];
    case Figure::Kind::LandedOutside: return std::accumulate(t.landings.begin(), t.landings.end(), t.landed_beyond_square);
    case Figure::Kind::HazardousImpacts: return std::accumulate(t.hazardous.begin(), t.hazardous.end(), t.hazardous_beyond_square);
    case Figure::Kind::PlaneCrossings: {
      const auto& bands = t.planes[plane_of[f.plane]].by_height;
      return std::accumulate(bands.begin(), bands.end(), std::uint64_t{0});
    }
    case Figure::Kind::PlaneHazards: return t.planes[plane_of[f.plane]].hazardous.sum;
  }
  return 0;
}

}  // namespace

FieldComparison compare_fields(const std::vector<scenario::Scenario>& designs, int threads, assess::Progress* progress,
                               const std::function<void(std::size_t, const scenario::Scenario&, std::uint64_t, std::uint64_t, std::uint64_t)>& on_design,
                               std::uint64_t segment_objects) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::unique_ptr<FieldSimulator>> sims;
  for (const auto& s : designs) {
    scenario::Scenario d = s;
    d.run.seed = designs.front().run.seed;  // common random numbers
    d.field.objects_simulated = designs.front().field.objects_simulated;
    sims.push_back(std::make_unique<FieldSimulator>(d));
  }
  // Each design's planes in the first's order, by name. A figure is named, and judged, by the
  // first design's energies and receptors: every design must count by the same ones.
  const scenario::FieldSpec& first_field = designs.front().field;
  const auto& first_planes = first_field.planes;
  std::vector<std::vector<std::size_t>> plane_of(designs.size());
  for (std::size_t d = 0; d < designs.size(); ++d) {
    const scenario::FieldSpec& f = designs[d].field;
    for (const auto& [key, value, first_value] : {std::tuple{"field.person_energy", f.person_energy, first_field.person_energy},
                                                  std::tuple{"field.vehicle_energy", f.vehicle_energy, first_field.vehicle_energy}})
      if (value != first_value)
        throw scenario::InputError(designs[d].file, std::nullopt, key, fmt::format("{:g} J", value),
                                   fmt::format("expected the first design's {:g} J: compared designs must count hazardous objects by the same energies", first_value));
    for (const auto& p : first_planes) {
      const auto& planes = f.planes;
      const auto it = std::find_if(planes.begin(), planes.end(), [&](const auto& q) { return q.name == p.name; });
      if (it == planes.end())
        throw scenario::InputError(designs[d].file, std::nullopt, "field.planes", "",
                                   fmt::format("the first design's plane '{}' is missing: compared designs need the same planes (by name)", p.name));
      if (it->receptor != p.receptor)
        throw scenario::InputError(designs[d].file, std::nullopt, "field.planes", p.name,
                                   fmt::format("the plane '{}' guards another receptor than the first design's: expected the same receptor for each plane compared", p.name));
      plane_of[d].push_back(static_cast<std::size_t>(it - planes.begin()));
    }
  }
  const std::vector<Figure> figure = figures_of(designs.front().field);
  const std::size_t figures = figure.size(), nd = designs.size();
  const auto n = static_cast<std::uint64_t>(designs.front().field.objects_simulated);
  // Each design's weight per object of each stratum (per metre travelled).
  std::vector<std::vector<double>> weight;
  for (const auto& sim : sims) weight.push_back(weights_per_object(*sim, n));
  // The one paired comparison (assess::run_paired): each design's objects run as j232 hazard
  // runs them (objects 0..n-1, each drawn from the same seed and index in every design), a
  // segment at a time, each thrown object's own count of every figure handed over in object
  // order (whole counts, exact in a double); added in blocks of the runner's chunk, each count
  // carrying its design's weight per object of its stratum.
  const std::uint64_t per_chunk = objects_per_chunk(n);
  std::vector<HazardRun> runs;
  for (const auto& sim : sims) runs.push_back(empty_run(*sim));
  assess::PairedRuns paired;
  paired.designs = nd, paired.figures = figures, paired.units = n;
  paired.block = per_chunk;
  paired.segment = std::max<std::uint64_t>(1, segment_objects / per_chunk) * per_chunk;
  paired.run = [&](std::size_t d, std::uint64_t first, std::uint64_t count, const assess::UnitSink& sink) {
    if (progress) progress->total = static_cast<long long>(count), progress->done = 0;  // (each design's run counts its own)
    if (on_design) on_design(d, designs[d], first, count, n);
    ObjectRows rows;
    rows.width = figures;
    rows.count = [&](const ObjectOutcome& o, const ObjectWatch& watch, double* row) {
      const bool thrown = counted_thrown(o.fate);
      for (std::size_t j = 0; j < figures; ++j) row[j] = thrown ? static_cast<double>(count_of(figure[j], watch, plane_of[d])) : 0.0;
    };
    rows.sink = sink;
    run_hazard_objects(*sims[d], n, first, count, runs[d], threads, progress, &rows);
  };
  paired.value = [&](std::size_t d, std::uint64_t i, std::size_t, double own) {
    return 1000 * weight[d][static_cast<std::size_t>(i % sims[d]->strata())] * own;
  };
  const assess::PairedSums total = assess::run_paired(paired);
  J232_CHECK(total.units == n || !assess::cluster::is_writer());  // rank 0 added every object once
  FieldComparison out;
  out.objects = n, out.seed = designs.front().run.seed;
  for (std::size_t d = 0; d < nd; ++d) {
    FieldDesign fd;
    fd.file = designs[d].file, fd.title = designs[d].title;
    // The heaviest weight one more event of each figure could carry, by j232 hazard's rule:
    // among the strata that can make it (a hazardous one needs the energy) or made it.
    std::vector<Stratum> strata(weight[d].size());
    for (std::size_t j = 0; j < figures; ++j) {
      for (std::size_t k = 0; k < strata.size(); ++k)
        strata[k] = {{events_of(figure[j], runs[d].strata[k], plane_of[d]), 0}, 1000 * weight[d][k],
                     sims[d]->stratum(k).energy_bound >= figure[j].threshold};
      fd.figures.push_back({figure[j].name, quasi_poisson(total.sum[total.own(d, j)], total.squares[total.own(d, j)], heaviest_weight(strata))});
    }
    if (d > 0)
      for (std::size_t j = 0; j < figures; ++j) {
        const std::size_t at = total.versus_first(d, j);
        const double mean = total.diff[at];
        const double variance = std::max(0.0, total.diff_squares[at] - mean * mean / static_cast<double>(n));
        // No object differed: the difference this run could have missed is about what 3.69
        // objects (Garwood's upper end for none seen) of the heavier weight would make.
        const double missed = -std::log(0.025) * 1000 * std::max(*std::max_element(weight[0].begin(), weight[0].end()),
                                                                   *std::max_element(weight[d].begin(), weight[d].end()));
        const double half = total.differing[at] == 0 ? missed : 1.959963984540054 * std::sqrt(variance);
        fd.differences.push_back({figure[j].name, {mean, mean - half, mean + half}, total.differing[at]});
      }
    // The design's whole run, summarised as j232 hazard summarises one: its hazard
    // distances, P(struck), planes.
    fd.hazard = summarise(*sims[d], runs[d]);
    fd.range = designs[d].field.range;
    fd.acceptable_probability = -std::expm1(-designs[d].field.presented_area / designs[d].field.acceptable_area);
    out.designs.push_back(std::move(fd));
  }
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace j232::field
