#pragma once
// The command-line options that set a run's overrides (j232 run and j232 batch).
#include <CLI/CLI.hpp>
#include <string>

#include "report/assessment_folder.hpp"

namespace j232::cli {

using report::RunOverrides;

// --replicates, --seed (any unsigned 64-bit value, or refused) and --threads on `cmd`.
void add_run_overrides(CLI::App& cmd, RunOverrides& overrides, const std::string& whose);
// --until-settled, --target-half-width and --estimator (run and batch: a comparison runs fixed replicates).
void add_stop_rule_options(CLI::App& cmd, RunOverrides& overrides);
// --trajectories K (run and batch).
void add_trajectories_option(CLI::App& cmd, RunOverrides& overrides);
// --uncertainty (run).
void add_uncertainty_option(CLI::App& cmd, RunOverrides& overrides);

}  // namespace j232::cli
