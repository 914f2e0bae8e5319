// `j232 uq`: how much a scenario's verdict rests on its uncertain inputs.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <map>
#include <set>
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
#include "random/stream.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario_reader.hpp"
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
  std::string reuse;     // a finished study's uq.csv whose assessments are taken, not rerun
  std::size_t recheck = 8;  // of those, how many are rerun and must come out the same
};

// The assessments of a finished study (its uq.csv) taken in place of running them, but for
// `recheck` of them chosen at random, which are run again and must reproduce the file's
// numbers exactly: a shipped study checked, and its report rebuilt, in a fraction of its
// time. The file must be of this study: the same inputs, outputs and draws.
class Reuse {
 public:
  Reuse(const UqOptions& o, const scenario::Scenario& nominal, const study::UncertaintyPlan& plan, const std::vector<study::UqOutput>& outputs) {
    if (o.reuse.empty()) return;
    table_ = report::read_uncertainty_csv(o.reuse);
    auto& t = *table_;
    std::vector<std::string> expected;
    for (const auto& in : plan.inputs) expected.push_back(report::csv_text_cell(in.parameter));
    for (const auto& out : outputs) expected.push_back(out.name);
    if (t.columns != expected) {
      std::string names;
      for (const auto& e : expected) names += (names.empty() ? "" : ",") + e;
      throw scenario::InputError(o.reuse, 1, "header", "its inputs and outputs",
                                 fmt::format("this study's: {} (the file is of another study)", names));
    }
    const std::size_t runs = (plan.inputs.size() + 2) * plan.base_draws;
    if (t.cells.size() != runs)
      throw scenario::InputError(o.reuse, static_cast<int>(t.cells.size()) + 1, "rows", std::to_string(t.cells.size()),
                                 fmt::format("{} assessments, as this study has ({} base draws x ({} inputs + 2))", runs, plan.base_draws,
                                             plan.inputs.size()));
    for (std::size_t run = 0; run < t.cells.size(); ++run) {
      auto& out = t.runs[run].outputs;
      out.assign(t.cells[run].begin() + static_cast<std::ptrdiff_t>(plan.inputs.size()), t.cells[run].end());
      // A J232 draw's verdict is judged again against this scenario's required P(pass) (the
      // file's was judged against its own): from P(pass) from every nail, as the study does.
      if (!nominal.field.present && out.size() == outputs.size() && outputs.back().name == "passes" && outputs[1].name == "p_pass_exact")
        out.back() = out[1] >= nominal.criteria.required_pass_probability ? 1.0 : 0.0;
    }
    // Which to run again: a partial Fisher-Yates shuffle on a keyed stream of the seed.
    std::vector<std::size_t> order(runs);
    for (std::size_t i = 0; i < runs; ++i) order[i] = i;
    random::Stream pick(nominal.run.seed, 0, 0, random::Purpose::Recheck);
    for (std::size_t i = 0; i < std::min(o.recheck, runs); ++i) {
      const std::size_t j = i + static_cast<std::size_t>(pick.uniform() * static_cast<double>(runs - i));
      std::swap(order[i], order[std::min(j, runs - 1)]);
      rerun_.insert(order[i]);
    }
  }
  bool active() const { return table_.has_value(); }
  std::size_t rerun_count() const { return rerun_.size(); }
  std::optional<study::UqRun> recall(std::size_t run) const {
    if (!table_ || rerun_.count(run)) return std::nullopt;
    return table_->runs[run];
  }
  // A rerun assessment against the file's: every output, its cut-off share and limit alike.
  void compare(std::size_t run, const study::UqRun& now) {
    if (!table_ || !rerun_.count(run)) return;
    const study::UqRun& then = table_->runs[run];
    if (now.outputs == then.outputs && now.cut_off_share == then.cut_off_share && now.cut_off_limit == then.cut_off_limit) return;
    std::string what = "its cut-off share or limit";
    for (std::size_t k = 0; k < now.outputs.size() && k < then.outputs.size(); ++k)
      if (now.outputs[k] != then.outputs[k]) {
        what = fmt::format("{}: {} in the file, {} now", table_->columns[k + table_->columns.size() - now.outputs.size()], then.outputs[k], now.outputs[k]);
        break;
      }
    differing_.push_back(fmt::format("assessment {} (line {}): {}", run + 1, table_->lines[run], what));
  }
  // After the study: every taken assessment's inputs were this study's draws, and every rerun
  // one came out the same; otherwise refused, naming the first that did not.
  void verify(const study::UncertaintyResult& r) const {
    if (!table_) return;
    for (std::size_t run = 0; run < r.values.size(); ++run)
      for (std::size_t i = 0; i < r.values[run].size(); ++i)
        if (r.values[run][i] != table_->cells[run][i])
          throw scenario::InputError(table_->file, table_->lines[run], table_->columns[i], fmt::format("{}", table_->cells[run][i]),
                                     fmt::format("{}, this study's draw {} (the file is of another study)", r.values[run][i], run + 1));
    if (!differing_.empty())
      throw scenario::InputError(table_->file, std::nullopt, "--recheck", fmt::format("{} assessments run again", rerun_.size()),
                                 fmt::format("{} of them differ from the file (made by another program or from other inputs); first: {}",
                                             differing_.size(), differing_.front()));
  }

 private:
  std::optional<report::UncertaintyTable> table_;
  std::set<std::size_t> rerun_;
  std::vector<std::string> differing_;
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
  const auto kept = journal.hooks();
  std::optional<Reuse> reuse;
  if (!o.reuse.empty()) {
    const auto nominal = scenario::read_scenario(o.scenario);
    reuse.emplace(o, nominal, study::uncertainty_plan(nominal), study::uq_outputs(nominal));
    fmt::print("Reusing {}: {} assessments run again to check it\n", terminal_safe(o.reuse), reuse->rerun_count());
  }
  const study::UncertaintyJournal hooks{[&](std::size_t run) { return reuse ? reuse->recall(run) : kept.recall(run); },
                                        [&](std::size_t run, const study::UqRun& v) {
                                          if (reuse) reuse->compare(run, v);
                                          kept.record(run, v);
                                        }};
  study::UncertaintyResult r;
  {
    const report::StepCounter counter("assessment");
    r = study::run_uncertainty(o.scenario, o.threads, std::cref(counter), &hooks);
  }
  if (reuse) reuse->verify(r);
  auto j = report::uncertainty_json(r);
  if (reuse)  // (outside what the shipped reports' check compares)
    j["provenance"] = {{"reused_from", o.reuse}, {"assessments_run_again", reuse->rerun_count()}};
  report::write_atomically(out.staged("uq.csv"), report::uncertainty_csv(r));
  report::write_atomically(out.staged("uq.html"), report::uncertainty_html(report::as_saved(j)));  // drawn from the file as saved, as redraw draws it
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
  cmd->add_option("--reuse", o->reuse,
                  "A finished study's uq.csv (of these inputs): take its assessments instead of running them, but for --recheck of "
                  "them, which are run again and must come out the same; refused otherwise")
      ->excludes(cmd->get_option("--resume"));
  cmd->add_option("--recheck", o->recheck, "With --reuse: how many of its assessments, chosen at random, are run again")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000))
      ->needs(cmd->get_option("--reuse"));
  return [o] { return uq(*o); };
}

}  // namespace j232::cli
