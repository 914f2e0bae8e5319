// `j232 uq`: how much a scenario's verdict rests on its uncertain inputs.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <map>
#include <optional>
#include <fmt/format.h>
#include <memory>

#include "assess/cluster.hpp"
#include "cli/run_options.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "report/output_folder.hpp"
#include "report/terminal_progress.hpp"
#include "report/atomic_file.hpp"
#include "report/text_safety.hpp"
#include "report/uncertainty_report.hpp"
#include "study/uncertainty.hpp"
#include "report/result_files.hpp"

namespace j232::cli {
namespace {

using report::terminal_safe;

struct UqOptions {
  std::string scenario;
  std::string out = "results/uq";
  int threads = 0;
  bool resume = false;
};

// The study's journal, DIR/uq-journal.csv: a first line naming the inputs' digest, then a
// line per finished assessment with its outputs written exactly (17 significant digits),
// flushed as each finishes. An interrupted study leaves it; `--resume` takes the
// assessments it holds when the digest matches. Removed when the study completes.
class Journal {
 public:
  Journal(std::string path, std::string digest, bool resume) : path_(std::move(path)), digest_(std::move(digest)) {
    const std::string header = "# j232 uq journal " + digest_;
    // In an MPI job rank 0 reads the journal and every rank takes the same assessments from it.
    std::string text;
    if (resume && assess::cluster::is_writer()) {
      std::ifstream file(path_);
      text.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
    }
    if (assess::cluster::size() > 1) assess::cluster::broadcast_from_writer(text);
    if (resume) {
      std::istringstream in(text);
      std::string line;
      if (std::getline(in, line) && line == header) {
        while (std::getline(in, line)) {
          std::vector<double> v;  // the outputs, the cut-off share and its commonest limit
          char* end = line.data();
          const auto run = std::strtoull(end, &end, 10);
          bool whole = end != line.data();
          while (whole && *end == ',') {
            char* start = end + 1;
            v.push_back(std::strtod(start, &end));
            whole = end != start;
          }
          // A line cut short by the interruption is not kept (the study also refuses one of
          // another number of outputs than its own).
          if (whole && *end == '\0' && v.size() > 2) {
            study::UqRun kept;
            kept.outputs.assign(v.begin(), v.end() - 2);
            kept.cut_off_share = v[v.size() - 2];
            kept.cut_off_limit = static_cast<int>(v.back());
            kept_[run] = kept;
          }
        }
      } else if (!text.empty()) {
        fmt::print("{}: made from other inputs or another program: starting afresh\n", terminal_safe(path_));
      }
    }
    if (!assess::cluster::is_writer()) return;  // rank 0 keeps the journal
    out_ = std::fopen(path_.c_str(), kept_.empty() ? "w" : "a");
    if (!out_) throw report::FileError(fmt::format("{}: cannot be written", path_));
    if (kept_.empty()) std::fprintf(out_, "%s\n", header.c_str());
    std::fflush(out_);
  }
  ~Journal() {
    if (out_) std::fclose(out_);
  }
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;
  std::size_t kept() const { return kept_.size(); }
  study::UncertaintyJournal hooks() {
    return {[this](std::size_t run) -> std::optional<study::UqRun> {
              const auto it = kept_.find(run);
              if (it == kept_.end()) return std::nullopt;
              return it->second;
            },
            [this](std::size_t run, const study::UqRun& v) {
              if (!out_) return;
              std::string line = fmt::format("{}", run);
              for (double x : v.outputs) line += fmt::format(",{:.17g}", x);
              line += fmt::format(",{:.17g},{}", v.cut_off_share, v.cut_off_limit);
              std::fprintf(out_, "%s\n", line.c_str());
              std::fflush(out_);
            }};
  }
  void remove() {
    if (!out_) return;
    std::fclose(out_);
    out_ = nullptr;
    std::remove(path_.c_str());
  }

 private:
  std::string path_, digest_;
  std::map<std::size_t, study::UqRun> kept_;
  std::FILE* out_ = nullptr;
};

int uq(const UqOptions& o) {
  report::OutputFolder out(o.out, {"uq.csv", "uq.html", "uq.json"});
  Journal journal(out.folder() + "/uq-journal.csv", report::inputs_digest(o.scenario, RunOverrides{}), o.resume);
  if (journal.kept()) fmt::print("Resuming: {} assessments kept from the journal\n", journal.kept());
  const auto hooks = journal.hooks();
  study::UncertaintyResult r;
  {
    const report::StepCounter counter("assessment");
    r = study::run_uncertainty(o.scenario, o.threads, std::cref(counter), &hooks);
  }
  const auto j = report::uncertainty_json(r);
  report::write_atomically(out.staged("uq.csv"), report::uncertainty_csv(r));
  report::write_atomically(out.staged("uq.html"), report::uncertainty_html(j));
  report::write_atomically(out.staged("uq.json"), report::json_text(j) + "\n");
  out.commit();
  journal.remove();
  fmt::print("{}\n{} inputs{}, {} assessments of {}\n", terminal_safe(r.title), r.plan.inputs.size(),
             r.plan.defaults ? " (default set of estimated inputs)" : "", r.outputs.size(),
             r.field ? fmt::format("{} objects", r.plan.objects) : fmt::format("{} replicates", r.plan.replicates));
  // The headline: P(pass), or a field's figure the inputs are ranked by.
  const auto& headline = r.output_info[r.field ? r.smooth_output : 0];
  const auto& p = j["outputs"][headline.name];
  fmt::print("{} over the inputs' uncertainty: median {:.4g}, 5-95 % {:.4g} to {:.4g}{}\n", r.field ? terminal_safe(headline.words) : "P(pass)",
             p["q50"].get<double>(), p["q05"].get<double>(), p["q95"].get<double>(), headline.unit);
  fmt::print("Robust verdict: {} ({:.1f} % of draws {})\n", j["robust_verdict"].get<std::string>(), 100 * j["share_of_draws_passing"].get<double>(),
             r.field ? "acceptable beyond the deck" : "pass");
  const auto& s = r.indices[r.smooth_output];  // smooth in the inputs: P(pass) from every nail, a field's flux
  if (s.variance > 0) {
    fmt::print("What drives {} (total Sobol' index, 95 % interval):\n",
               r.field ? terminal_safe(r.output_info[r.smooth_output].words) : "P(pass) from every nail");
    std::vector<std::size_t> order(r.plan.inputs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return s.total[a].estimate > s.total[b].estimate; });
    bool flagged = false;
    for (auto i : order) {
      const bool noise = study::leaves_unit_interval(s.total[i]);
      flagged = flagged || noise;
      fmt::print("  {:<34} {:.3f} ({:.3f} to {:.3f}){}\n", terminal_safe(r.plan.inputs[i].parameter), s.total[i].estimate, s.total[i].low,
                 s.total[i].high, noise ? "  (!)" : "");
    }
    if (flagged)
      fmt::print("  (!) the interval leaves [0, 1], where an index lies, by more than 0.05: at {} base draws it is as much noise as effect\n",
                 r.plan.base_draws);
    if (r.half_indices) {
      double moved = 0;
      const auto& half = (*r.half_indices)[r.smooth_output];
      if (half.variance > 0)
        for (std::size_t i = 0; i < order.size(); ++i) moved = std::max(moved, std::abs(half.total[i].estimate - s.total[i].estimate));
      fmt::print("  from {} to {} base draws the total indices moved by at most {:.3f}\n", r.plan.base_draws / 2, r.plan.base_draws, moved);
    }
  }
  for (std::size_t i = 0; i < r.warnings.size() && i < 5; ++i) fmt::print("WARNING: {}\n", terminal_safe(r.warnings[i]));
  if (r.warnings.size() > 5) fmt::print("WARNING: {} more draws like these (uq.json lists them)\n", r.warnings.size() - 5);
  fmt::print("Wrote {}/uq.html, uq.json and uq.csv\n", terminal_safe(o.out));
  return kOk;
}

}  // namespace

Runner add_uq_command(CLI::App& app) {
  auto o = std::make_shared<UqOptions>();
  CLI::App* cmd = app.add_subcommand("uq", "How much the verdict rests on uncertain inputs: robust verdict and Sobol' sensitivity indices");
  cmd->add_option("scenario", o->scenario, "Scenario file (TOML); its [uncertainty] table, or the default estimated inputs")->required();
  cmd->add_option("--out", o->out, "Output folder for uq.html, uq.json and uq.csv")->capture_default_str();
  cmd->add_option("--threads", o->threads, "Worker threads, 0 = all cores")->check(CLI::Range(0, 1024))->each([](const std::string& t) { warn_threads_beyond_cores(std::atoll(t.c_str())); });
  cmd->add_flag("--resume", o->resume, "Continue an interrupted study in the same folder: keep the assessments it finished");
  return [o] { return uq(*o); };
}

}  // namespace j232::cli
