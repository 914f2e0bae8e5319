// `j232 hazard`: the thrown-object hazard of a mower at work in a field (docs/model.md §9),
// from a scenario with [field] to hazard.html, hazard.json and hazard.csv.
#include <fmt/format.h>
#include <memory>

#include "cli/commands.hpp"
#include "cli/run_options.hpp"
#include "cli/exit_codes.hpp"
#include "report/hazard_folder.hpp"
#include "report/text_safety.hpp"

namespace j232::cli {
namespace {

using report::terminal_safe;

struct HazardOptions {
  std::string scenario;
  std::string units = "si";
  std::string out = "hazard";
  report::HazardOverrides overrides;
};

int hazard(const HazardOptions& o) {
  report::HazardOverrides overrides = o.overrides;
  overrides.units = report::display_units(o.units);
  const report::HazardOutcome outcome = report::hazard_to_folder(o.scenario, overrides, o.out);
  if (!outcome.writer) return kOk;
  fmt::print("{}", terminal_safe(outcome.summary_text));
  fmt::print("  Wrote {}/hazard.html, {}/hazard.json and {}/hazard.csv\n", terminal_safe(o.out), terminal_safe(o.out), terminal_safe(o.out));
  return outcome.valid ? kOk : kInvalid;
}

}  // namespace

Runner add_hazard_command(CLI::App& app) {
  auto o = std::make_shared<HazardOptions>();
  CLI::App* cmd = app.add_subcommand(
      "hazard", "Simulate a mower at work in a field strewn with objects ([field]) and assess the thrown-object hazard around it "
                "(exit 0 assessed, 4 invalid)");
  cmd->add_option("scenario", o->scenario, "Scenario file (TOML) with a [field] table; see scenarios/field/")->required();
  cmd->add_option("--objects", o->overrides.objects, "Objects to simulate (default: the scenario's field.objects_simulated)")
      ->check(CLI::Range(1LL, 1'000'000'000LL));
  add_unsigned_option(*cmd, "--seed", o->overrides.seed, "Random seed (default: the scenario's)");
  cmd->add_option("--threads", o->overrides.threads, "Threads (0: all cores; default: the scenario's)")
      ->check(CLI::Range(0, 1024))
      ->each([](const std::string& t) { warn_threads_beyond_cores(std::atoll(t.c_str())); });
  cmd->add_option("--out", o->out, "Output folder for hazard.html, hazard.json and hazard.csv")->capture_default_str();
  cmd->add_option("--units", o->units,
                  "Units of hazard.html and the summary: si (m, m/s, J, per km) or us (ft, mph, ft-lb, per mile); hazard.json and "
                  "hazard.csv keep SI")
      ->capture_default_str();
  return [o] { return hazard(*o); };
}

}  // namespace j232::cli
