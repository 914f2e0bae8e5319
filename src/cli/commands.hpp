#pragma once
#include <CLI/CLI.hpp>
#include <functional>

namespace j232::cli {

// Each command registers its subcommand and returns the function that runs it
// (returning an exit code from exit_codes.hpp) once the command line is parsed.
using Runner = std::function<int()>;
Runner add_impact_command(CLI::App& app);
Runner add_run_command(CLI::App& app);
Runner add_scene_command(CLI::App& app);
Runner add_batch_command(CLI::App& app);
Runner add_sweep_command(CLI::App& app);
Runner add_compare_command(CLI::App& app);
Runner add_uq_command(CLI::App& app);
Runner add_calibrate_command(CLI::App& app);
Runner add_trace_command(CLI::App& app);
Runner add_hazard_command(CLI::App& app);
Runner add_redraw_command(CLI::App& app);

}  // namespace j232::cli
