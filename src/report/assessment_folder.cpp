#include "report/assessment_folder.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <map>
#include <thread>

#include "assess/runner.hpp"
#include "assess/cluster.hpp"
#include "assess/summary.hpp"
#include "assess/trajectories.hpp"
#include "report/atomic_file.hpp"
#include "report/board_views.hpp"
#include "report/output_folder.hpp"
#include "report/terminal_progress.hpp"
#include "report/compliance_report.hpp"
#include "report/result_files.hpp"
#include "report/scene_view.hpp"
#include "report/uncertainty_report.hpp"
#include "report/drivers_report.hpp"
#include "study/drivers.hpp"
#include "study/uncertainty.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario.hpp"
#include "scenario/scenario_reader.hpp"
#include "scenario/toml_reader.hpp"
#include "scene/j232_setup.hpp"
#include "scene/markers.hpp"

#include "j232/version.hpp"

namespace j232::report {

namespace {

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
  f.add(fmt::format("{} {} {} {}", o.replicates, o.seed ? std::to_string(*o.seed) : "-1", j232::version, j232::git_revision));
  if (o.trajectories > 0) f.add(fmt::format(" trajectories {}", o.trajectories));
  if (o.uncertainty) f.add(" uncertainty");
  if (o.drivers) f.add(" drivers");
  if (o.for_comparison) f.add(" no stop rule");
  if (o.until_settled) f.add(" until settled");
  if (o.target_half_width) f.add(fmt::format(" half-width {:.17g}", *o.target_half_width));
  if (o.estimator) f.add(fmt::format(" estimator {}", static_cast<int>(*o.estimator)));
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

// A kept nail path for the 3D view, with its trail from a replay of the nail (the same
// nail: replays are deterministic): what a click on it shows, and where it marked.
ScenePath scene_path(const assess::Simulator& sim, const assess::Trajectory& t, const std::string& scenario_file) {
  ScenePath out;
  out.points = t.points;
  out.why = t.why;
  out.fate = flight::fate_name(t.fate);
  const assess::NailReplay replay = sim.replay(t.replicate, t.nail);
  const flight::FlightResult& f = replay.outcome.flight;
  std::map<std::string, int> touched;
  for (const auto& e : replay.events) {
    if (e.kind == flight::FlightEvent::Kind::Bounce) ++touched[std::string(scene::name(e.surface))];
    if (e.kind == flight::FlightEvent::Kind::GuardPass) ++touched["through a guard"];
    if (e.kind == flight::FlightEvent::Kind::Board && e.mark > 0) out.marks.emplace_back(e.point, e.mark);
  }
  std::string touches;
  for (const auto& [what, n] : touched) touches += fmt::format("{}{} {}", touches.empty() ? "" : ", ", what, n);
  out.info.push_back(fmt::format("replicate {}, nail {} (kept: {})", t.replicate, t.nail, t.why));
  out.info.push_back(fmt::format("fate: {}", flight::fate_name(f.fate)));
  out.info.push_back(fmt::format("blade strikes: {}; bounces: {}; gentle contacts: {}", f.strikes, f.bounces, f.gentle_contacts));
  if (!touches.empty()) out.info.push_back("touched: " + touches);
  if (f.trace.exit != flight::Exit::Inside) {
    out.info.push_back("way out: " + sim.exit_name(f.trace.exit, f.trace.exit_index));
    if (f.trace.first_exit != f.trace.exit || f.trace.first_exit_index != f.trace.exit_index)
      out.info.push_back("first left by: " + sim.exit_name(f.trace.first_exit, f.trace.first_exit_index));
  }
  for (const auto& [p, kind] : out.marks)
    out.info.push_back(fmt::format("{} of the board at {:.0f} mm up", kind == 2 ? "puncture" : "hit", 1000 * p.z()));
  out.info.push_back(fmt::format("whole trail: j232 trace {} --replicate {} --nail {}", scenario_file, t.replicate, t.nail));
  return out;
}

RunOutcome assess_to_folder(const std::string& scenario_file, const RunOverrides& o, const std::string& out) {
  scenario::Scenario s = scenario::read_scenario(scenario_file);
  if (o.replicates > 0) s.run.replicates = o.replicates;
  if (o.seed) s.run.seed = *o.seed;
  if (o.threads >= 0) s.run.threads = o.threads;
  if (o.until_settled) s.run.until_settled = true;
  if (o.target_half_width) s.run.target_half_width = o.target_half_width;
  if (o.estimator) s.run.estimator = *o.estimator;
  if (o.for_comparison) s.run.target_half_width.reset(), s.run.until_settled = false;  // every design runs the same replicates
  const assess::Simulator simulator(s);

  // The folder is locked and checked before the simulation, so a bad --out costs nothing.
  std::vector<std::string> files = {"marks.csv", "report.html", "result.json"};
  if (o.uncertainty) files.insert(files.begin(), {"uq.csv", "uq.html", "uq.json"});
  // The scene in 3D beside the report, when this build has three.js.
  const bool view = scene_view_available();
  if (view) files.insert(files.begin(), "scene.html");
  OutputFolder folder(out, files);
  StreamedFile marks(folder.staged("marks.csv"));
  marks.write(marks_csv_header());
  std::string buffer;
  assess::NotableNails notable;
  const assess::MarkSink sink = [&](const assess::MarkRow& row) {
    if (o.trajectories > 0) notable.add(row);
    append_marks_csv_row(buffer, row, simulator);
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
  const assess::Summary sum = assess::summarise(a, s, assess::kExactDraws);

  Provenance p{j232::version, j232::git_revision, utc_now(), digest(scenario_file, s.meshes, o),
               a.threads,     a.wall_seconds,     {},        assess::cluster::size()};
  p.files.push_back({"marks.csv", marks.bytes(), marks.digest()});
  // The report shows result.json's numbers; its own size and digest go into result.json.
  RunOutcome outcome{result_json(s, a, sum, p), summary_text(s, sum), std::nullopt};
  if (o.uncertainty) {
    // The scenario's own uncertainty study beside the run (its [uncertainty] seed and
    // replicates are the scenario's, not the run's overrides), summarised in the report.
    study::UncertaintyResult study;
    {
      const StepCounter counter("uncertainty study: assessment");
      study = study::run_uncertainty(scenario_file, s.run.threads, std::cref(counter));
    }
    const auto uq = uncertainty_json(study);
    write_atomically(folder.staged("uq.csv"), uncertainty_csv(study));
    write_atomically(folder.staged("uq.html"), uncertainty_html(as_saved(uq)));  // drawn from the file as saved, as redraw draws it
    write_atomically(folder.staged("uq.json"), json_text(uq) + "\n");
    outcome.result["uncertainty"] = uncertainty_summary_json(uq);
    outcome.summary_text += uncertainty_summary_text(outcome.result["uncertainty"]);
  }
  if (o.drivers && !o.for_comparison && sum.validity.valid) {
    // What most moves the deciding criterion: each uncertain input at its range's ends, paired
    // with the scenario as written (the scenario's seed and the study's replicates).
    study::Drivers drivers;
    {
      const StepCounter counter("what moves the verdict: run");
      drivers = study::deciding_drivers(scenario_file, sum.deciding, s.run.threads, std::cref(counter));
    }
    outcome.result["deciding_inputs"] = drivers_json(drivers, outcome.result["deciding_criterion"].get<std::string>());
    outcome.summary_text += drivers_text(outcome.result["deciding_inputs"]);
  }
  // What the page's pictures need of the run and its scene goes into result.json, and the page
  // is drawn from the file as saved: `j232 redraw result.json` draws the same page.
  outcome.result["pictures"] = pictures_json(s, a, simulator.scene().soup());
  require_finite(outcome.result["pictures"], "pictures");
  const std::string html = compliance_report_html(as_saved(outcome.result));
  Fnv html_digest;
  html_digest.add(html);
  outcome.result["provenance"]["files"].push_back({{"name", "report.html"}, {"bytes", html.size()}, {"fnv1a64", html_digest.hex()}});
  write_atomically(folder.staged("report.html"), html);
  if (view) {
    std::vector<ScenePath> paths;
    for (const auto& t : a.trajectories) paths.push_back(scene_path(simulator, t, scenario_file));
    const std::string page = scene_view_html(s, simulator.scene().soup(), scene::scene_guards(s), scene::mower_markers(s), paths);
    Fnv page_digest;
    page_digest.add(page);
    outcome.result["provenance"]["files"].push_back({{"name", "scene.html"}, {"bytes", page.size()}, {"fnv1a64", page_digest.hex()}});
    write_atomically(folder.staged("scene.html"), page);
  }
  write_atomically(folder.staged("result.json"), json_text(outcome.result) + "\n");
  folder.commit();
  if (recorder) outcome.design = std::move(*recorder).finish(s, a, &sum);
  return outcome;
}

}  // namespace j232::report
