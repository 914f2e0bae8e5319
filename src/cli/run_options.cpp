#include "cli/run_options.hpp"

#include <fmt/format.h>

#include "scenario/toml_reader.hpp"

namespace j232::cli {

void add_trajectories_option(CLI::App& cmd, RunOverrides& o) {
  cmd.add_option("--trajectories", o.trajectories,
                 "Keep and draw the whole paths of the first K struck nails, plus every nail that marked the operator zone or "
                 "punctured the board (up to 100 of each, chosen at random)")
      ->check(CLI::Range(0, 1000));
}

void add_uncertainty_option(CLI::App& cmd, RunOverrides& o) {
  cmd.add_flag("--uncertainty", o.uncertainty,
               "Also run the scenario's uncertainty study (as j232 uq: its [uncertainty] inputs or the default estimated ones) and "
               "summarise it in the report; writes uq.html, uq.json and uq.csv beside it");
}

void add_run_overrides(CLI::App& cmd, RunOverrides& o, const std::string& whose) {
  cmd.add_option("--replicates", o.replicates, fmt::format("Replicates of the whole test (overrides {} [run] replicates)", whose))
      ->check(CLI::Range(1LL, 100'000'000LL));
  cmd.add_option_function<std::string>(
         "--seed",
         [&o](const std::string& text) {
           const auto seed = scenario::parse_unsigned64(text);
           if (!seed) throw CLI::ValidationError("--seed", "expected a whole number from 0 to 18446744073709551615, got " + text);
           o.seed = *seed;
         },
         fmt::format("Random seed, 0 to 2^64-1 (overrides {} [run] seed)", whose))
      ->type_name("UINT64");
  cmd.add_option("--threads", o.threads, "Worker threads, 0 = all cores (overrides [run] threads)")->check(CLI::Range(0, 1024));
}

}  // namespace j232::cli
