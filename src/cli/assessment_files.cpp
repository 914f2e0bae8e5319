#include "cli/assessment_files.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <thread>

#include "assess/runner.hpp"
#include "assess/cluster.hpp"
#include "assess/summary.hpp"
#include "cli/output_folder.hpp"
#include "cli/progress_bar.hpp"
#include "assess/trajectories.hpp"
#include "report/atomic_file.hpp"
#include "report/compliance_report.hpp"
#include "report/result_files.hpp"
#include "report/uncertainty_report.hpp"
#include "study/uncertainty.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario.hpp"
#include "scenario/toml_reader.hpp"

#ifndef J232_GIT_REVISION
#define J232_GIT_REVISION "unknown"
#endif

namespace j232::cli {
namespace {


std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string digest(const std::string& scenario_file, const std::vector<scenario::MeshFile>& meshes, const RunOverrides& o) {
  Fnv f;
  const auto separator = [&] { f.add("\xff"); };
  f.add(file_bytes(scenario_file));
  separator();
  for (const auto& m : meshes) f.add(file_bytes(m.path)), separator();
  // Not the thread count: results do not depend on it.
  f.add(fmt::format("{} {} {} {}", o.replicates, o.seed ? std::to_string(*o.seed) : "-1", J232_VERSION, J232_GIT_REVISION));
  if (o.trajectories > 0) f.add(fmt::format(" trajectories {}", o.trajectories));
  if (o.uncertainty) f.add(" uncertainty");
  if (o.for_comparison) f.add(" no stop rule");
  separator();
  return f.hex();
}

}  // namespace

std::string inputs_digest(const std::string& scenario_file, const RunOverrides& o) {
  try {
    return digest(scenario_file, scenario::read_scenario(scenario_file).meshes, o);
  } catch (const scenario::InputError&) {
    return "unreadable";  // a bad scenario is never current
  }
}

RunOutcome assess_to_folder(const std::string& scenario_file, const RunOverrides& o, const std::string& out) {
  scenario::Scenario s = scenario::read_scenario(scenario_file);
  if (o.replicates > 0) s.run.replicates = o.replicates;
  if (o.seed) s.run.seed = *o.seed;
  if (o.threads >= 0) s.run.threads = o.threads;
  if (o.for_comparison) s.run.target_half_width.reset();  // every design runs the same replicates
  const assess::Simulator simulator(s);

  // The folder is locked and checked before the simulation, so a bad --out costs nothing.
  std::vector<std::string> files = {"marks.csv", "report.html", "result.json"};
  if (o.uncertainty) files.insert(files.begin(), {"uq.csv", "uq.html", "uq.json"});
  OutputFolder folder(out, files);
  StreamedFile marks(folder.staged("marks.csv"));
  marks.write(report::marks_csv_header());
  std::string buffer;
  assess::NotableNails notable;
  const assess::MarkSink sink = [&](const assess::MarkRow& row) {
    if (o.trajectories > 0) notable.add(row);
    report::append_marks_csv_row(buffer, row, simulator);
    if (buffer.size() > (1u << 20)) marks.write(buffer), buffer.clear();
  };
  assess::Progress progress;
  assess::Assessment a;
  std::optional<study::DesignRecorder> recorder;
  if (o.for_comparison) recorder.emplace(static_cast<std::uint64_t>(s.run.replicates));
  {
    ProgressBar bar(progress);
    a = assess::run_assessment(simulator, s.run.threads, &progress, sink, recorder ? recorder->sink() : assess::ReplicateSink{});
  }
  marks.write(buffer);
  marks.close();
  if (o.trajectories > 0) {
    a.trajectories = assess::trace_nails(simulator, o.trajectories, notable);
    a.trajectories_not_kept = notable.not_kept();
  }
  const assess::Summary sum = assess::summarise(a, s);

  report::Provenance p{J232_VERSION, J232_GIT_REVISION, utc_now(), digest(scenario_file, s.meshes, o), a.threads, a.wall_seconds, {},
                       assess::cluster::size()};
  p.files.push_back({"marks.csv", marks.bytes(), marks.digest()});
  // The report shows result.json's numbers; its own size and digest go into result.json.
  RunOutcome outcome{report::result_json(s, a, sum, p), report::summary_text(s, sum), std::nullopt};
  if (o.uncertainty) {
    // The scenario's own uncertainty study beside the run (its [uncertainty] seed and
    // replicates are the scenario's, not the run's overrides), summarised in the report.
    study::UncertaintyResult study;
    {
      const StepCounter counter("uncertainty study: assessment");
      study = study::run_uncertainty(scenario_file, s.run.threads, std::cref(counter));
    }
    const auto uq = report::uncertainty_json(study);
    report::write_atomically(folder.staged("uq.csv"), report::uncertainty_csv(study));
    report::write_atomically(folder.staged("uq.html"), report::uncertainty_html(uq));
    report::write_atomically(folder.staged("uq.json"), uq.dump(2) + "\n");
    outcome.result["uncertainty"] = report::uncertainty_summary_json(uq);
    outcome.summary_text += report::uncertainty_summary_text(outcome.result["uncertainty"]);
  }
  const std::string html = report::compliance_report_html(s, a, sum, outcome.result, simulator.scene().soup());
  Fnv html_digest;
  html_digest.add(html);
  outcome.result["provenance"]["files"].push_back({{"name", "report.html"}, {"bytes", html.size()}, {"fnv1a64", html_digest.hex()}});
  report::write_atomically(folder.staged("report.html"), html);
  report::write_atomically(folder.staged("result.json"), outcome.result.dump(2) + "\n");
  folder.commit();
  if (recorder) outcome.design = std::move(*recorder).finish(s, a);
  return outcome;
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

void add_run_overrides(CLI::App& cmd, RunOverrides& o, const std::string& whose) {
  cmd.add_option("--replicates", o.replicates, fmt::format("Replicates of the whole test (overrides {} [run] replicates)", whose))
      ->check(CLI::Range(1LL, 100'000'000LL));
  cmd.add_option_function<std::string>(
         "--seed",
         [&o](const std::string& text) {
           const auto seed = scenario::parse_unsigned64(text);
           if (!seed) throw CLI::ValidationError("--seed", "expected a whole number from 0 to 18446744073709551615, got " + text);
           o.seed = *seed;
         },
         fmt::format("Random seed, 0 to 2^64-1 (overrides {} [run] seed)", whose))
      ->type_name("UINT64");
  cmd.add_option("--threads", o.threads, "Worker threads, 0 = all cores (overrides [run] threads)")->check(CLI::Range(0, 1024));
}

}  // namespace j232::cli
