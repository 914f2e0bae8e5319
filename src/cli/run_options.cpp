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

void add_stop_rule_options(CLI::App& cmd, RunOverrides& o) {
  cmd.add_flag("--until-settled", o.until_settled,
               "Run batches (the first of --replicates, then growing by half the replicates so far) until the verdict's 95 % interval "
               "lies on one side of the required probability, or [run] max_replicates (sets [run] until_settled)");
  cmd.add_option_function<double>(
         "--target-half-width", [&o](double w) { o.target_half_width = w; },
         "Run batches (as --until-settled) until the verdict's 95 % interval is at most this far either side of its estimate, "
         "or [run] max_replicates (overrides [run] target_half_width)")
      ->check(CLI::Range(0.001, 0.5))
      ->type_name("W");
  cmd.add_option_function<std::string>(
         "--estimator",
         [&o](const std::string& text) {
           using E = scenario::RunSpec::Estimator;
           o.estimator = text == "replicates" ? E::Replicates : text == "every-nail" ? E::EveryNail : E::Narrower;
         },
         "The P(pass) the verdict rests on: narrower (default: the narrower interval of the two), replicates (the share of "
         "replicates that passed) or every-nail (the exact sum over every nail's outcome) (overrides [run] estimator)")
      ->check(CLI::IsMember({"narrower", "replicates", "every-nail"}))
      ->type_name("NAME");
}

}  // namespace j232::cli
