// `j232 hazard`: the thrown-object hazard of a mower at work in a field (docs/model.md §9),
// from a scenario with [field] to hazard.html, hazard.json and hazard.csv.
#include <ctime>
#include <fmt/format.h>
#include <memory>
#include <optional>

#include "assess/cluster.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "field/hazard_run.hpp"
#include "j232/version.hpp"
#include "report/atomic_file.hpp"
#include "report/hazard_report.hpp"
#include "report/output_folder.hpp"
#include "report/terminal_progress.hpp"
#include "report/text_safety.hpp"
#include "scenario/scenario_reader.hpp"

namespace j232::cli {
namespace {

using report::terminal_safe;

struct HazardOptions {
  std::string scenario;
  std::string out = "hazard";
  long long objects = 0;  // 0: the scenario's
  std::optional<unsigned long long> seed;
  int threads = -1;
};

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

int hazard(const HazardOptions& o) {
  scenario::Scenario s = scenario::read_scenario(o.scenario);
  if (o.objects > 0) s.field.objects_simulated = o.objects;
  if (o.seed) s.run.seed = *o.seed;
  if (o.threads >= 0) s.run.threads = o.threads;
  const field::FieldSimulator sim(s);
  // Every rank of an MPI job simulates its share; rank 0 alone writes.
  const bool writer = assess::cluster::is_writer();
  std::optional<report::OutputFolder> folder;
  if (writer) folder.emplace(o.out, std::vector<std::string>{"hazard.csv", "hazard.html", "hazard.json"});
  assess::Progress progress;
  field::HazardRun run = [&] {
    report::ProgressBar bar(progress);
    return field::run_hazard(sim, s.run.threads, &progress);
  }();
  if (!writer) return kOk;
  const field::HazardSummary sum = field::summarise(sim, run);
  const report::HazardProvenance p{j232::version, j232::git_revision, utc_now(), s.run.seed, run.threads, assess::cluster::size(), run.wall_seconds};
  const auto result = report::hazard_json(sim, run, sum, p);
  report::write_atomically(folder->staged("hazard.csv"), report::hazard_csv(sum));
  report::write_atomically(folder->staged("hazard.html"), report::hazard_html(sim, run, sum, result));
  report::write_atomically(folder->staged("hazard.json"), result.dump(2) + "\n");
  folder->commit();
  fmt::print("{}: thrown-object hazard in the field\n{}", terminal_safe(s.title), terminal_safe(report::hazard_text(sum)));
  fmt::print("  {} objects in {:.2f} s on {} thread(s){}: {:.0f} objects/s.\n  Wrote {}/hazard.html, {}/hazard.json and {}/hazard.csv\n",
             run.objects(), run.wall_seconds, run.threads, p.ranks > 1 ? fmt::format(" in each of {} MPI ranks", p.ranks) : "", run.wall_seconds > 0 ? static_cast<double>(run.objects()) / run.wall_seconds : 0.0,
             terminal_safe(o.out), terminal_safe(o.out), terminal_safe(o.out));
  return sum.valid ? kOk : kInvalid;
}

}  // namespace

Runner add_hazard_command(CLI::App& app) {
  auto o = std::make_shared<HazardOptions>();
  CLI::App* cmd = app.add_subcommand(
      "hazard", "Simulate a mower at work in a field strewn with objects ([field]) and assess the thrown-object hazard around it "
                "(exit 0 assessed, 4 invalid)");
  cmd->add_option("scenario", o->scenario, "Scenario file (TOML) with a [field] table; see scenarios/field/")->required();
  cmd->add_option("--objects", o->objects, "Objects to simulate (default: the scenario's field.objects_simulated)")->check(CLI::Range(1LL, 1'000'000'000LL));
  cmd->add_option("--seed", o->seed, "Random seed (default: the scenario's)");
  cmd->add_option("--threads", o->threads, "Threads (0: all cores; default: the scenario's)")->check(CLI::Range(0, 1024));
  cmd->add_option("--out", o->out, "Output folder for hazard.html, hazard.json and hazard.csv")->capture_default_str();
  return [o] { return hazard(*o); };
}

}  // namespace j232::cli
