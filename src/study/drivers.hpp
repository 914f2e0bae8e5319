#pragma once
// What most moves a verdict (docs/model.md §6d): each input of the scenario's uncertainty
// set (its [uncertainty] inputs, or j232's default set of estimated inputs) set in turn to
// each end of its range (each value of a discrete input), every other input as the scenario
// has it, and run with the scenario's seed and the study's replicates. Common random
// numbers: each change against the scenario as written is judged replicate by replicate
// (study::compare_records), so its interval is the paired one. The inputs are ranked by the
// largest change they make to the deciding criterion's mean share.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>
#include "study/compare.hpp"

namespace j232::study {

struct DriverEnd {
  std::string value;      // as the range or values list writes it ("80 J/m", "plywood")
  std::string verdict;    // the run's own verdict at this value: "passes", "fails", "invalid"
  double share = 0;       // the deciding criterion's mean share
  MeanInterval change;    // minus the scenario's, paired (95 %)
  double p_pass_exact = 0;  // P(pass) from every nail (the replicates' share where not computed)
};

struct Driver {
  std::string input, basis;
  std::vector<DriverEnd> ends;
  double largest_change = 0;  // the largest |change| over its valid ends
};

struct Drivers {
  int criterion = 0;          // the deciding criterion (assess::Category)
  std::uint64_t replicates = 0;
  unsigned long long seed = 0;
  double share = 0;           // the scenario's own deciding share at these replicates
  double p_pass_exact = 0;
  bool default_inputs = true;  // j232's default set (else the scenario's [uncertainty] inputs)
  std::vector<Driver> ranked;  // largest change first
};

// Throws scenario::InputError when an end makes a scenario the reader refuses. A J232
// scenario only (a field has no deciding criterion). `on_run` is told before each run.
Drivers deciding_drivers(const std::string& scenario_file, int criterion, int threads,
                         const std::function<void(std::size_t, std::size_t)>& on_run = {});

}  // namespace j232::study
