#pragma once
// The command-line options that set a run's overrides (j232 run and j232 batch).
#include <CLI/CLI.hpp>
#include <string>

#include "report/assessment_folder.hpp"

namespace j232::cli {

using report::RunOverrides;

// An option that takes a whole number from 0 to 2^64-1 into `target`: a negative or any other
// text is refused by name, never wrapped round (CLI11 reads "-1" into an unsigned as 2^64-1).
template <class Target>
CLI::Option* add_unsigned_option(CLI::App& cmd, const std::string& name, Target& target, const std::string& help);

// --replicates, --seed (any unsigned 64-bit value, or refused) and --threads on `cmd`.
void add_run_overrides(CLI::App& cmd, RunOverrides& overrides, const std::string& whose);
// --until-settled, --target-half-width and --estimator (run and batch: a comparison runs fixed replicates).
void add_stop_rule_options(CLI::App& cmd, RunOverrides& overrides);
// --trajectories K (run and batch).
void add_trajectories_option(CLI::App& cmd, RunOverrides& overrides);
// --uncertainty (run).
void add_uncertainty_option(CLI::App& cmd, RunOverrides& overrides);
// --drivers: also the inputs that most move the deciding criterion, in the report.
void add_drivers_option(CLI::App& cmd, RunOverrides& overrides);

// --threads beyond this machine's cores: said on standard error (a run is no faster for it).
void warn_threads_beyond_cores(long long threads);

}  // namespace j232::cli
