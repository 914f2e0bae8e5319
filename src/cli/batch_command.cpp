// `j232 batch`: many scenarios, one after another (each run already uses every core,
// so running them side by side would only make each slower), with one summary.
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <memory>

#include "cli/assessment_files.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "report/atomic_file.hpp"
#include "report/batch_summary.hpp"
#include "scenario/input_error.hpp"

namespace j232::cli {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

struct BatchOptions {
  std::vector<std::string> scenarios;
  std::string out = "results/batch";
  bool resume = false;
  RunOverrides overrides;
};

// One folder per scenario, named after its file; a repeated name gets -2, -3, ...
std::vector<std::string> folder_names(const std::vector<std::string>& files) {
  std::map<std::string, int> seen;
  std::vector<std::string> names;
  for (const auto& f : files) {
    const std::string stem = fs::path(f).stem().string();
    const int n = ++seen[stem];
    names.push_back(n == 1 ? stem : fmt::format("{}-{}", stem, n));
  }
  return names;
}

// The folder's results, if they are complete and were made from these very inputs.
std::optional<json> current_result(const fs::path& folder, const std::string& digest) {
  for (const char* f : {"result.json", "report.html", "marks.csv"})
    if (!fs::exists(folder / f)) return std::nullopt;
  std::ifstream in(folder / "result.json");
  const json r = json::parse(in, nullptr, false);
  if (r.is_discarded() || !r.contains("provenance") || r["provenance"].value("inputs_digest", "") != digest) return std::nullopt;
  return r;
}

int batch(const BatchOptions& o) {
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) throw scenario::InputError("", std::nullopt, "--out", o.out, "cannot create the output folder: " + ec.message());
  const auto names = folder_names(o.scenarios);
  std::vector<report::BatchRow> rows;
  bool internal_error = false;
  for (std::size_t i = 0; i < o.scenarios.size(); ++i) {
    const std::string& file = o.scenarios[i];
    report::BatchRow row{file, names[i], std::nullopt, {}, false};
    const fs::path folder = fs::path(o.out) / names[i];
    fmt::print("[{}/{}] {}: ", i + 1, o.scenarios.size(), file);
    std::fflush(stdout);
    try {
      if (o.resume) {
        row.result = current_result(folder, inputs_digest(file, o.overrides));
        row.resumed = row.result.has_value();
      }
      if (!row.result) row.result = assess_to_folder(file, o.overrides, folder.string()).result;
      const json& r = *row.result;
      fmt::print("{} (P(pass) {:.3f}, 95 % {:.3f} to {:.3f}){}\n", r["verdict"] == "passes" ? "PASSES" : "FAILS",
                 r["pass_probability"]["estimate"].get<double>(), r["pass_probability"]["low"].get<double>(),
                 r["pass_probability"]["high"].get<double>(), row.resumed ? "  [current results kept]" : "");
    } catch (const scenario::InputError& e) {
      row.result.reset();
      row.error = e.what();
      fmt::print("REFUSED\n  {}\n", e.what());
    } catch (const std::exception& e) {
      row.result.reset();
      row.error = fmt::format("internal error: {}", e.what());
      internal_error = true;
      fmt::print("INTERNAL ERROR\n  {}\n", e.what());
    }
    rows.push_back(std::move(row));
  }
  const fs::path dir(o.out);
  const json summary = report::batch_summary_json(rows);
  report::write_atomically((dir / "summary.csv").string(), report::batch_summary_csv(rows));
  report::write_atomically((dir / "summary.html").string(), report::batch_summary_html(rows));
  report::write_atomically((dir / "summary.json").string(), summary.dump(2) + "\n");
  fmt::print("{} of {} scenarios pass, {} fail, {} refused. Wrote {}/summary.html, summary.json and summary.csv\n",
             summary["passed"].get<std::size_t>(), rows.size(), summary["failed"].get<std::size_t>(),
             summary["refused"].get<std::size_t>(), o.out);
  if (internal_error) return kInternal;
  if (summary["refused"].get<std::size_t>() > 0) return kBadInput;
  return summary["all_passed"].get<bool>() ? kOk : kFails;
}

}  // namespace

Runner add_batch_command(CLI::App& app) {
  auto o = std::make_shared<BatchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "batch", "Assess many scenarios and summarise them (exit 0 all pass, 1 some fail, 2 some refused as bad input)");
  cmd->add_option("scenarios", o->scenarios, "Scenario files (TOML); shell globs welcome: scenarios/*.toml")->required();
  cmd->add_option("--out", o->out, "Output folder: one subfolder per scenario, plus summary.html/.json/.csv")->capture_default_str();
  cmd->add_flag("--resume", o->resume, "Keep results that are complete and were made from the same inputs and program");
  cmd->add_option("--replicates", o->overrides.replicates, "Replicates of each test (overrides each scenario's)")->check(CLI::PositiveNumber);
  cmd->add_option("--seed", o->overrides.seed, "Random seed (overrides each scenario's)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--threads", o->overrides.threads, "Worker threads, 0 = all cores")->check(CLI::NonNegativeNumber);
  return [o] { return batch(*o); };
}

}  // namespace j232::cli
