#pragma once
// P(pass) from the nails themselves (docs/model.md §5.6b). A replicate's four counts are
// sums over its 150 nails, and the nails are independent by construction (each a pure
// function of seed, replicate and nail; its feed station fixed by its number). So P(pass)
// is a known function of each station's distribution of a nail's counted marks by
// category, which R replicates sample R n_s times: estimated from all the nails, it is
// smooth where the share of passing replicates moves in steps of 1/R, and it resolves
// tails that "1.000" cannot. It is computed exactly by dynamic programming over the counts
// up to the limits; its interval is a Bayesian bootstrap over each station's outcome
// frequencies (Dirichlet weights), with a weak prior on the single marks no nail made.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "assess/tally.hpp"
#include "scenario/scenario.hpp"

namespace j232::assess {

// A nail's counted marks by category, packed in one key (8 bits each, capped at 255).
using NailMarks = std::array<int, kCategories>;
std::uint32_t marks_key(const flight::FlightResult& nail);
NailMarks marks_of_key(std::uint32_t key);

// How often a nail fed at each station made each combination of counted marks.
struct StationOutcomes {
  std::vector<std::map<std::uint32_t, std::uint64_t>> by_station;

  void add(int station, std::uint32_t key);
  void merge(const StationOutcomes& other);
  std::uint64_t nails(std::size_t station) const;
};

// Bootstrap draws for the exact estimate's interval in a run (about 1 s on two cores).
inline constexpr int kExactDraws = 400;

struct ExactPass {
  bool computed = false;
  std::string not_computed;  // why, when not
  double value = 0;          // from the observed frequencies
  double low = 0, high = 1;  // 95 %, Bayesian bootstrap
  int draws = 0;
  std::uint64_t states = 0;  // of the dynamic programme
};

// The largest count of category c a test of `nails` nails may have and still pass it
// (the replicate judgement's own rule: share <= limit, with its rounding slack).
int allowed_count(const scenario::CriteriaSpec& criteria, int category, int nails);

// P(all four counts within their limits) for independent nails, nail i fed at station
// i mod S, each station's outcomes with the given probabilities (each list sums to 1).
// Exact, by dynamic programming over the counts up to the limits.
using OutcomeDistribution = std::vector<std::pair<NailMarks, double>>;
double pass_probability(const std::vector<OutcomeDistribution>& stations, int nails, const std::array<int, kCategories>& allowed);

// The estimate and its interval from the recorded outcomes (`draws` bootstrap draws, 0:
// the value alone). Not computed for the `marks` denominator (a share of all marks needs
// the total as a fifth dimension) or limits so loose that the counts exceed `max_states`.
ExactPass exact_pass(const StationOutcomes& outcomes, int nails, const scenario::CriteriaSpec& criteria, std::uint64_t seed, int draws = 400,
                     std::uint64_t max_states = 4'000'000);

}  // namespace j232::assess
