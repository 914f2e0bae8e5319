// `j232 batch`: many scenarios, one after another (each run already uses every core,
// so running them side by side would only make each slower), with one summary.
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <set>
#include <memory>

#include "cli/run_options.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "report/output_folder.hpp"
#include "report/atomic_file.hpp"
#include "report/batch_summary.hpp"
#include "report/hazard_folder.hpp"
#include "report/comparison_report.hpp"
#include "report/text_safety.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario_reader.hpp"
#include "report/result_files.hpp"

namespace j232::cli {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

struct BatchOptions {
  std::vector<std::string> scenarios;
  std::string out = "results/batch";
  bool resume = false, compare = false;
  RunOverrides overrides;
};

// One folder per scenario, named after its file (made safe: letters, digits, - _ . and
// no leading dot); a repeated name gets -2, -3, ...
std::vector<std::string> folder_names(const std::vector<std::string>& files) {
  std::set<std::string> used{"summary.csv", "summary.html", "summary.json"};
  std::vector<std::string> names;
  for (const auto& f : files) {
    const std::string stem = report::safe_folder_name(fs::path(f).stem().string());
    std::string name = stem;
    for (int n = 2; used.count(name); ++n) name = fmt::format("{}-{}", stem, n);
    used.insert(name);
    names.push_back(name);
  }
  return names;
}

// The bytes of a file and their digest match what result.json recorded.
bool matches(const fs::path& file, const json& recorded) {
  std::ifstream in(file, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  report::Fnv f;
  f.add(bytes);
  return in.good() || in.eof() ? recorded.value("bytes", std::uint64_t{0}) == bytes.size() && recorded.value("fnv1a64", "") == f.hex()
                               : false;
}

// The folder's results, if they are a complete set made from these very inputs.
std::optional<json> current_result(const fs::path& folder, const std::string& digest) {
  std::ifstream in(folder / "result.json");
  if (!in) return std::nullopt;
  const json r = json::parse(in, nullptr, false);
  if (r.is_discarded() || !r.contains("provenance") || r["provenance"].value("inputs_digest", "") != digest) return std::nullopt;
  // Every file it lists as written (marks.csv and report.html; scene.html when the build
  // draws it) still as written.
  const json& files = r["provenance"].value("files", json::array());
  bool marks = false, report = false;
  for (const auto& f : files) {
    if (!f.is_object() || !matches(folder / f.value("name", "?"), f)) return std::nullopt;
    marks |= f.value("name", "") == "marks.csv", report |= f.value("name", "") == "report.html";
  }
  return marks && report ? std::optional<json>(r) : std::nullopt;
}

int batch(const BatchOptions& given) {
  BatchOptions o = given;
  if (o.compare) {
    if (o.resume)
      throw scenario::InputError("", std::nullopt, "--compare", "",
                                 "without --resume: a comparison pairs every design's replicates, which "
                                 "kept results do not hold");
    if (o.scenarios.size() < 2) throw scenario::InputError("", std::nullopt, "--compare", "", "at least two scenarios to compare");
    // Common random numbers: every design runs the first's seed and replicates.
    const scenario::Scenario first = scenario::read_scenario(o.scenarios.front());
    if (!o.overrides.seed) o.overrides.seed = first.run.seed;
    if (o.overrides.replicates <= 0) o.overrides.replicates = first.run.replicates;
    o.overrides.for_comparison = true;
  }
  // Locked and checked before the first scenario runs.
  std::vector<std::string> files = {"summary.csv", "summary.html", "summary.json"};
  if (o.compare) files.insert(files.begin(), {"compare.csv", "compare.html", "compare.json"});
  report::OutputFolder out(o.out, files);
  std::vector<study::DesignRecord> designs;
  const auto names = folder_names(o.scenarios);
  std::vector<report::BatchRow> rows;
  bool internal_error = false;
  for (std::size_t i = 0; i < o.scenarios.size(); ++i) {
    const std::string& file = o.scenarios[i];
    report::BatchRow row{file, names[i], std::nullopt, std::nullopt, {}, false};
    const fs::path folder = fs::path(o.out) / names[i];
    fmt::print("[{}/{}] {}: ", i + 1, o.scenarios.size(), report::terminal_safe(file));
    std::fflush(stdout);
    try {
      if (scenario::read_scenario(file).field.present) {
        // A field scenario: its thrown-object hazard (run again each time: --resume keeps J232 results only).
        if (o.compare) throw scenario::InputError(file, std::nullopt, "field", "", "batch --compare pairs J232 designs; compare field scenarios with j232 compare");
        report::HazardOverrides h;
        h.seed = o.overrides.seed, h.threads = o.overrides.threads;
        const report::HazardOutcome outcome = report::hazard_to_folder(file, h, folder.string());
        row.hazard = outcome.result;
        fmt::print("{} ({:.0f} thrown per km)\n", outcome.valid ? "FIELD HAZARD ASSESSED" : "FIELD HAZARD INVALID (no assessment)",
                   outcome.result["objects"]["thrown_per_km"].get<double>());
        rows.push_back(std::move(row));
        continue;
      }
      if (o.resume) {
        row.result = current_result(folder, report::inputs_digest(file, o.overrides));
        row.resumed = row.result.has_value();
      }
      if (!row.result) {
        report::RunOutcome run = report::assess_to_folder(file, o.overrides, folder.string());
        row.result = std::move(run.result);
        if (run.design && (*row.result)["verdict"] != "invalid") designs.push_back(std::move(*run.design));
      }
      const json& r = *row.result;
      const std::string verdict = r["verdict"].get<std::string>();
      fmt::print("{} (P(pass) {:.3f}, 95 % {:.3f} to {:.3f}){}\n",
                 verdict == "passes"    ? "PASSES"
                 : verdict == "invalid" ? "INVALID (no verdict)"
                                        : "FAILS",
                 r["pass_probability"]["estimate"].get<double>(), r["pass_probability"]["low"].get<double>(),
                 r["pass_probability"]["high"].get<double>(), row.resumed ? "  [current results kept]" : "");
    } catch (const scenario::InputError& e) {
      row.result.reset();
      row.error = e.what();
      fmt::print("REFUSED\n  {}\n", report::terminal_safe(e.what()));
    } catch (const std::exception& e) {
      row.result.reset();
      row.error = fmt::format("internal error: {}", e.what());
      internal_error = true;
      fmt::print("INTERNAL ERROR\n  {}\n", report::terminal_safe(e.what()));
    }
    rows.push_back(std::move(row));
  }
  json comparison = nullptr;
  if (o.compare) {
    // The designs that ran and gave a verdict, in the order given (the first is the baseline).
    if (designs.size() < 2) {
      fmt::print("No comparison: fewer than two scenarios gave a verdict\n");
    } else {
      const study::Comparison c = study::compare_records(designs, *o.overrides.seed);
      comparison = report::comparison_json(c);
      report::write_atomically(out.staged("compare.csv"), report::comparison_csv(c));
      report::write_atomically(out.staged("compare.html"), report::comparison_html(comparison));
      report::write_atomically(out.staged("compare.json"), report::json_text(comparison) + "\n");
    }
  }
  const json summary = report::batch_summary_json(rows, comparison);
  report::write_atomically(out.staged("summary.csv"), report::batch_summary_csv(rows));
  report::write_atomically(out.staged("summary.html"), report::batch_summary_html(rows, comparison));
  report::write_atomically(out.staged("summary.json"), report::json_text(summary) + "\n");
  out.commit();
  fmt::print("{} of {} scenarios pass, {} fail, {} invalid, {} refused{}. Wrote {}/summary.html, summary.json and summary.csv{}\n",
             summary["passed"].get<std::size_t>(), rows.size(), summary["failed"].get<std::size_t>(), summary["invalid"].get<std::size_t>(),
             summary["refused"].get<std::size_t>(),
             summary["fields"].get<std::size_t>() > 0 ? fmt::format(", {} field scenario(s) assessed for hazard", summary["fields"].get<std::size_t>()) : "",
             report::terminal_safe(o.out),
             comparison.is_null() ? "" : ", and the comparison of the designs in compare.html, compare.json and compare.csv");
  if (internal_error) return kInternal;
  if (summary["refused"].get<std::size_t>() > 0) return kBadInput;
  if (summary["invalid"].get<std::size_t>() > 0) return kInvalid;
  return summary["all_passed"].get<bool>() ? kOk : kFails;
}

}  // namespace

Runner add_batch_command(CLI::App& app) {
  auto o = std::make_shared<BatchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "batch", "Assess many scenarios and summarise them (exit 0 all pass, 1 some fail, 2 some refused as bad input, 4 some invalid)");
  cmd->add_option("scenarios", o->scenarios, "Scenario files (TOML); shell globs welcome: scenarios/*.toml")->required();
  cmd->add_option("--out", o->out, "Output folder: one subfolder per scenario, plus summary.html/.json/.csv")->capture_default_str();
  cmd->add_flag("--resume", o->resume, "Keep results that are complete and were made from the same inputs and program");
  cmd->add_flag("--compare", o->compare,
                "Also compare the scenarios as designs: all run with the first's seed and replicates (common random numbers), "
                "each judged against the first replicate by replicate (compare.html/.json/.csv, and in the summary)");
  add_run_overrides(*cmd, o->overrides, "each scenario's");
  add_drivers_option(*cmd, o->overrides);
  add_stop_rule_options(*cmd, o->overrides);
  add_trajectories_option(*cmd, o->overrides);
  return [o] { return batch(*o); };
}

}  // namespace j232::cli
