#include "report/hazard_folder.hpp"

#include <fmt/format.h>
#include <vector>

#include "assess/cluster.hpp"
#include "field/hazard_run.hpp"
#include "j232/version.hpp"
#include "report/atomic_file.hpp"
#include "report/hazard_report.hpp"
#include "report/output_folder.hpp"
#include "report/terminal_progress.hpp"
#include "scenario/scenario_reader.hpp"
#include "report/result_files.hpp"

namespace j232::report {

HazardOutcome hazard_to_folder(const std::string& scenario_file, const HazardOverrides& o, const std::string& out) {
  scenario::Scenario s = scenario::read_scenario(scenario_file);
  if (o.objects > 0) s.field.objects_simulated = o.objects;
  if (o.seed) s.run.seed = *o.seed;
  if (o.threads >= 0) s.run.threads = o.threads;
  const field::FieldSimulator sim(s);
  // Every rank of an MPI job simulates its share; rank 0 alone writes.
  HazardOutcome outcome;
  outcome.writer = assess::cluster::is_writer();
  std::optional<OutputFolder> folder;
  if (outcome.writer) folder.emplace(out, std::vector<std::string>{"hazard.csv", "hazard.html", "hazard.json"});
  assess::Progress progress;
  const field::HazardRun run = [&] {
    ProgressBar bar(progress);
    return field::run_hazard(sim, s.run.threads, &progress);
  }();
  if (!outcome.writer) return outcome;
  const field::HazardSummary sum = field::summarise(sim, run);
  const HazardProvenance p{j232::version, j232::git_revision, utc_now(), s.run.seed, run.threads, assess::cluster::size(), run.wall_seconds};
  outcome.result = hazard_json(sim, run, sum, p);
  write_atomically(folder->staged("hazard.csv"), hazard_csv(sum));
  write_atomically(folder->staged("hazard.html"), hazard_html(as_saved(outcome.result), o.units));
  write_atomically(folder->staged("hazard.json"), json_text(outcome.result) + "\n");
  folder->commit();
  outcome.valid = sum.valid;
  outcome.summary_text = fmt::format("{}: thrown-object hazard in the field\n{}", s.title, hazard_text(sum, run.strata.front().layout.range, o.units));
  // What the reader noticed in the file (a guard named as a flap without `kind`, a blade below
  // the skirt's foot) and cut-offs near the limit, as `j232 run` lists among its warnings
  // (hazard.json's `warnings`, hazard.html's list).
  for (const auto& w : sum.warnings) outcome.summary_text += fmt::format("  Warning: {}\n", w);
  outcome.summary_text += fmt::format("  {} objects in {:.2f} s on {} thread(s){}: {:.0f} objects/s.\n", run.objects(), run.wall_seconds, run.threads,
                                      p.ranks > 1 ? fmt::format(" in each of {} MPI ranks", p.ranks) : "",
                                      run.wall_seconds > 0 ? static_cast<double>(run.objects()) / run.wall_seconds : 0.0);
  return outcome;
}

}  // namespace j232::report
