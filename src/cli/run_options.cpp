#include "cli/run_options.hpp"

#include <fmt/format.h>
#include <optional>
#include <thread>

#include "scenario/toml_reader.hpp"

namespace j232::cli {

template <class Target>
CLI::Option* add_unsigned_option(CLI::App& cmd, const std::string& name, Target& target, const std::string& help) {
  return cmd
      .add_option_function<std::string>(
          name,
          [&target, name](const std::string& text) {
            const auto value = scenario::parse_unsigned64(text);
            if (!value) throw CLI::ValidationError(name, "expected a whole number from 0 to 18446744073709551615, got " + text);
            target = *value;
          },
          help)
      ->type_name("UINT64");
}
template CLI::Option* add_unsigned_option(CLI::App&, const std::string&, std::uint64_t&, const std::string&);
template CLI::Option* add_unsigned_option(CLI::App&, const std::string&, std::optional<std::uint64_t>&, const std::string&);
template CLI::Option* add_unsigned_option(CLI::App&, const std::string&, std::optional<unsigned long long>&, const std::string&);

void warn_threads_beyond_cores(long long threads) {
  const unsigned cores = std::thread::hardware_concurrency();
  if (cores > 0 && threads > static_cast<long long>(cores))
    fmt::print(stderr, "j232: warning: --threads {} is more than this machine's {} cores: the run is no faster for it\n", threads, cores);
}

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

void add_drivers_option(CLI::App& cmd, RunOverrides& o) {
  cmd.add_flag("--drivers", o.drivers,
               "Also find the inputs that most move the deciding criterion: each uncertain input (the [uncertainty] set, or the "
               "default estimated one) at its range's ends, paired runs of the study's replicates (27 runs of 50 "
               "replicates for the default set), in the report and result.json");
}

void add_run_overrides(CLI::App& cmd, RunOverrides& o, const std::string& whose) {
  cmd.add_option("--replicates", o.replicates, fmt::format("Replicates of the whole test (overrides {} [run] replicates)", whose))
      ->check(CLI::Range(1LL, 100'000'000LL));
  add_unsigned_option(cmd, "--seed", o.seed, fmt::format("Random seed, 0 to 2^64-1 (overrides {} [run] seed)", whose));
  cmd.add_option("--threads", o.threads, "Worker threads, 0 = all cores (overrides [run] threads)")
      ->check(CLI::Range(0, 1024))
      ->each([](const std::string& t) { warn_threads_beyond_cores(std::atoll(t.c_str())); });
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
