// `j232 run`: the J232 assessment of one scenario, from file to verdict and report.
#include <fmt/format.h>
#include <memory>

#include "cli/run_options.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "report/scene_view.hpp"
#include "report/text_safety.hpp"

namespace j232::cli {
namespace {

using report::terminal_safe;

struct RunOptions {
  std::string scenario;
  std::string out = "results";
  RunOverrides overrides;
};

int run(const RunOptions& o) {
  const report::RunOutcome outcome = report::assess_to_folder(o.scenario, o.overrides, o.out);
  const auto& p = outcome.result["provenance"];
  fmt::print("{}", terminal_safe(outcome.summary_text));
  fmt::print(
      "  {:.2f} s on {} thread(s){}: {:.0f} nails/s.\n  Wrote {}/report.html, {}/result.json and {}/marks.csv{}{}\n",
      p["wall_time_s"].get<double>(), p["threads"].get<int>(),
      p["ranks"].get<int>() > 1 ? fmt::format(" in each of {} MPI ranks", p["ranks"].get<int>()) : "", p["nails_per_second"].get<double>(),
      terminal_safe(o.out), terminal_safe(o.out), terminal_safe(o.out),
      report::scene_view_available() ? fmt::format(", the scene in 3D in {}/scene.html", terminal_safe(o.out)) : "",
      o.overrides.uncertainty ? fmt::format(", and the uncertainty study in {}/uq.html, uq.json and uq.csv", terminal_safe(o.out)) : "");
  const auto& verdict = outcome.result["verdict"];
  return verdict == "passes" ? kOk : verdict == "invalid" ? kInvalid : kFails;
}

}  // namespace

Runner add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd =
      app.add_subcommand("run", "Simulate the SAE J232 test of a scenario and judge it (exit 0 passes, 1 fails, 4 invalid: no verdict)");
  cmd->add_option("scenario", o->scenario, "Scenario file (TOML); see scenarios/")->required();
  add_run_overrides(*cmd, o->overrides, "the scenario's");
  add_stop_rule_options(*cmd, o->overrides);
  add_trajectories_option(*cmd, o->overrides);
  add_uncertainty_option(*cmd, o->overrides);
  add_drivers_option(*cmd, o->overrides);
  cmd->add_option("--out", o->out, "Output folder for report.html, result.json and marks.csv")->capture_default_str();
  return [o] { return run(*o); };
}

}  // namespace j232::cli
