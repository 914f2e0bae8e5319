// `j232 run`: the J232 assessment of one scenario, from file to verdict and report.
#include <fmt/format.h>
#include <memory>

#include "cli/assessment_files.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"

namespace j232::cli {
namespace {

struct RunOptions {
  std::string scenario;
  std::string out = "results";
  RunOverrides overrides;
};

int run(const RunOptions& o) {
  const RunOutcome outcome = assess_to_folder(o.scenario, o.overrides, o.out);
  const auto& p = outcome.result["provenance"];
  fmt::print("{}", outcome.summary_text);
  fmt::print("  {:.2f} s on {} thread(s): {:.0f} nails/s.\n  Wrote {}/report.html, {}/result.json and {}/marks.csv\n",
             p["wall_time_s"].get<double>(), p["threads"].get<int>(), p["nails_per_second"].get<double>(), o.out, o.out, o.out);
  return outcome.result["verdict"] == "passes" ? kOk : kFails;
}

}  // namespace

Runner add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Simulate the SAE J232 test of a scenario and judge it (exit 0 passes, 1 fails)");
  cmd->add_option("scenario", o->scenario, "Scenario file (TOML); see scenarios/")->required();
  cmd->add_option("--replicates", o->overrides.replicates, "Replicates of the whole test (overrides [run] replicates)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--seed", o->overrides.seed, "Random seed (overrides [run] seed)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--threads", o->overrides.threads, "Worker threads, 0 = all cores (overrides [run] threads)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", o->out, "Output folder for report.html, result.json and marks.csv")->capture_default_str();
  return [o] { return run(*o); };
}

}  // namespace j232::cli
