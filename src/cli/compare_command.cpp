// `j232 compare`: several designs judged against one another with common random numbers.
#include <algorithm>
#include <fmt/format.h>
#include <memory>

#include "cli/run_options.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "report/output_folder.hpp"
#include "report/terminal_progress.hpp"
#include "report/atomic_file.hpp"
#include "report/comparison_report.hpp"
#include "report/assessment_folder.hpp"
#include "report/version_comparison.hpp"
#include "report/hazard_report.hpp"
#include "scenario/input_error.hpp"
#include "report/text_safety.hpp"
#include "scenario/scenario.hpp"
#include "scenario/scenario_reader.hpp"
#include "study/compare.hpp"
#include "report/result_files.hpp"

namespace j232::cli {
namespace {

using report::terminal_safe;

struct CompareOptions {
  std::vector<std::string> scenarios;
  std::string out = "results/compare";
  std::string units = "si";
  RunOverrides overrides;
};

// Field scenarios compared: their hazard figures, paired object by object.
int compare_fields(const CompareOptions& o, std::vector<scenario::Scenario>& designs) {
  if (o.overrides.seed) designs.front().run.seed = *o.overrides.seed;
  if (o.overrides.replicates > 0)
    throw scenario::InputError("", std::nullopt, "--replicates", std::to_string(o.overrides.replicates),
                               "field scenarios simulate field.objects_simulated objects, not replicates (set it in the first design)");
  const int threads = o.overrides.threads >= 0 ? o.overrides.threads : designs.front().run.threads;
  report::OutputFolder out(o.out, {"compare.csv", "compare.html", "compare.json"});
  assess::Progress progress;
  field::FieldComparison c;
  {
    report::ProgressBar bar(progress);
    c = field::compare_fields(designs, threads, &progress,
                              [&](std::size_t d, const scenario::Scenario& s, std::uint64_t first, std::uint64_t count, std::uint64_t objects) {
                                fmt::print("[{}/{}] {} (objects {} to {} of {}, seed {})\n", d + 1, designs.size(), terminal_safe(s.title),
                                           first + 1, first + count, objects, designs.front().run.seed);
                                std::fflush(stdout);
                              });
  }
  const auto j = report::hazard_comparison_json(c);
  report::write_atomically(out.staged("compare.csv"), report::hazard_comparison_csv(c));
  const report::DisplayUnits units = report::display_units(o.units);
  report::write_atomically(out.staged("compare.html"), report::hazard_comparison_html(report::as_saved(j), units));
  report::write_atomically(out.staged("compare.json"), report::json_text(j) + "\n");
  out.commit();
  fmt::print("{}", terminal_safe(report::hazard_comparison_text(c, units)));
  fmt::print("Wrote {}/compare.html, compare.json and compare.csv\n", terminal_safe(o.out));
  return kOk;
}

bool is_result_file(const std::string& path) { return path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0; }

// An earlier result.json beside a scenario (run now, with the earlier run's replicates and
// seed unless overridden, into OUT/run) or beside another result.json: what moved.
int compare_with_earlier(const CompareOptions& o) {
  if (o.scenarios.size() != 2)
    throw scenario::InputError("", std::nullopt, "scenarios", fmt::format("{} files", o.scenarios.size()),
                               "an earlier result.json and one scenario (or one later result.json) to compare it with");
  const auto earlier = report::read_result_file(o.scenarios[0]);
  std::string now_file = o.scenarios[1];
  if (!is_result_file(now_file)) {
    RunOverrides run = o.overrides;
    if (run.replicates <= 0) run.replicates = earlier["replicates"].get<long long>();
    if (!run.seed) run.seed = earlier["provenance"]["seed"].get<unsigned long long>();
    fmt::print("Running {} ({} replicates, seed {}) to compare with {}\n", terminal_safe(now_file), run.replicates, *run.seed,
               terminal_safe(o.scenarios[0]));
    std::fflush(stdout);
    report::assess_to_folder(now_file, run, o.out + "/run");
    now_file = o.out + "/run/result.json";
  } else if (o.overrides.replicates > 0 || o.overrides.seed) {
    throw scenario::InputError("", std::nullopt, o.overrides.seed ? "--seed" : "--replicates", "",
                               "no run to set: both files are results (give a scenario to run one)");
  }
  const auto now = report::read_result_file(now_file);
  const auto c = report::compare_results(earlier, o.scenarios[0], now, now_file);
  report::OutputFolder out(o.out, {"versions.html", "versions.json"});
  report::write_atomically(out.staged("versions.html"), report::version_comparison_html(c));
  report::write_atomically(out.staged("versions.json"), report::json_text(c) + "\n");
  out.commit();
  fmt::print("{}", terminal_safe(report::version_comparison_text(c)));
  fmt::print("Wrote {}/versions.html and versions.json\n", terminal_safe(o.out));
  return kOk;
}

int compare(const CompareOptions& o) {
  const bool us = report::display_units(o.units).us;  // (a bad name refused before anything runs)
  if (us && is_result_file(o.scenarios.front()))
    throw scenario::InputError("", std::nullopt, "--units", o.units, "si: comparing results across versions gives shares of nails, which have no units");
  if (is_result_file(o.scenarios.front())) return compare_with_earlier(o);
  std::vector<scenario::Scenario> designs;
  for (const auto& file : o.scenarios) designs.push_back(scenario::read_scenario(file));  // every file checked before running
  std::size_t fields = 0;
  for (const auto& d : designs) fields += d.field.present ? 1 : 0;
  if (fields == designs.size()) return compare_fields(o, designs);
  if (fields > 0)
    // Named: the first design of the other kind than the first one's.
    throw scenario::InputError(std::find_if(designs.begin(), designs.end(),
                                            [&](const auto& d) { return d.field.present != designs.front().field.present; })
                                   ->file,
                               std::nullopt, "field", "", "compare either J232 test scenarios or field scenarios ([field]), not both");
  if (us)
    throw scenario::InputError(designs.front().file, std::nullopt, "--units", o.units,
                               "si: J232 test designs are compared by shares of nails, which have no units (--units us is for field scenarios)");
  if (o.overrides.replicates > 0) designs.front().run.replicates = o.overrides.replicates;
  if (o.overrides.seed) designs.front().run.seed = *o.overrides.seed;
  const int threads = o.overrides.threads >= 0 ? o.overrides.threads : designs.front().run.threads;
  report::OutputFolder out(o.out, {"compare.csv", "compare.html", "compare.json"});
  assess::Progress progress;
  study::Comparison c;
  {
    report::ProgressBar bar(progress);
    c = study::compare_designs(designs, threads, &progress, [&](std::size_t d, const scenario::Scenario& s) {
      progress.done = 0;
      fmt::print("[{}/{}] {} ({} replicates, seed {})\n", d + 1, designs.size(), terminal_safe(s.title), s.run.replicates, s.run.seed);
      std::fflush(stdout);
    });
  }
  const auto j = report::comparison_json(c);
  report::write_atomically(out.staged("compare.csv"), report::comparison_csv(c));
  report::write_atomically(out.staged("compare.html"), report::comparison_html(report::as_saved(j)));  // (as a redraw draws it)
  report::write_atomically(out.staged("compare.json"), report::json_text(j) + "\n");
  out.commit();
  fmt::print("{}", report::comparison_text(c));
  fmt::print("Wrote {}/compare.html, compare.json and compare.csv\n", terminal_safe(o.out));
  return kOk;
}

}  // namespace

Runner add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Compare designs with common random numbers: each design's shares and their differences from the first, with intervals");
  cmd->add_option("scenarios", o->scenarios,
                  "Two or more scenario files (TOML); the first is the reference. Or an earlier result.json and a scenario "
                  "(run now with its replicates and seed) or a later result.json: what moved between them")
      ->required()
      ->expected(2, -1);
  cmd->add_option("--out", o->out, "Output folder for compare.html, compare.json and compare.csv")->capture_default_str();
  cmd->add_option("--units", o->units,
                  "Field designs: units of compare.html and the table, si (m, per km) or us (ft, per mile); the JSON and CSV keep SI")
      ->capture_default_str();
  add_run_overrides(*cmd, o->overrides, "the first scenario's (every design runs with the first's)");
  return [o] { return compare(*o); };
}

}  // namespace j232::cli
