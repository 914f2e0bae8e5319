// `j232 sweep`: parameter studies over an impact case (report 445-1, Appendix A, first
// program; Figs 2.8-2.16) or a J232 scenario (P(pass) against a design parameter).
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <unistd.h>

#include "assess/cluster.hpp"
#include "cli/commands.hpp"
#include "cli/run_options.hpp"
#include "cli/exit_codes.hpp"
#include "report/atomic_file.hpp"
#include "scenario/input_error.hpp"
#include "study/sweep.hpp"
#include "report/sweep_report.hpp"

namespace j232::cli {
namespace {

struct SweepOptions {
  std::vector<std::string> files;
  std::string base, x, title, name;
  std::vector<std::string> series;
  std::string out = "results/sweeps";
  long long replicates = 0, objects = 0;
  int threads = 0;
};

class TerminalProgress : public study::SweepProgress {
 public:
  explicit TerminalProgress(std::string name) : name_(std::move(name)), on_(isatty(fileno(stderr)) != 0) {}
  ~TerminalProgress() override {
    if (on_) std::fprintf(stderr, "\r%60s\r", "");
  }
  void point(std::size_t done, std::size_t total) override {
    if (on_) std::fprintf(stderr, "\r%s: point %zu of %zu ", name_.c_str(), done, total), std::fflush(stderr);
  }

 private:
  std::string name_;
  bool on_;
};

void run_one(const study::SweepSpec& spec, const SweepOptions& o) {
  study::SweepTable table;
  {
    TerminalProgress progress(spec.name);
    table = study::run_sweep(spec, o.threads, &progress);
  }
  if (!assess::cluster::is_writer()) return;  // another rank of an MPI job: rank 0 writes
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) throw scenario::InputError("", std::nullopt, "--out", o.out, "cannot create the output folder: " + ec.message());
  const std::filesystem::path dir(o.out);
  std::vector<std::string> written{(dir / (spec.name + ".csv")).string()};
  report::write_atomically(written.front(), report::sweep_csv(spec, table));
  for (const auto& [suffix, svg] : report::sweep_charts(spec, table)) {
    written.push_back((dir / fmt::format("{}-{}.svg", spec.name, suffix)).string());
    report::write_atomically(written.back(), svg);
  }
  std::size_t invalid = 0;
  for (const auto& r : table.rows)
    if (!r.invalid.empty()) ++invalid, fmt::print("  Warning: not assessed: {}\n", r.invalid);
  fmt::print("{}: {} points ({} of {}{}). Wrote {}\n", spec.title, table.rows.size(), study::points_name(table.kind), spec.base,
             invalid ? fmt::format("; {} not assessed, named in the CSV's note column", invalid) : "", fmt::join(written, ", "));
}

int sweep(const SweepOptions& o) {
  if (o.files.empty() == o.base.empty())
    throw scenario::InputError("", std::nullopt, "sweep", "", "expected sweep files, or --base with --x (and optionally --series)");
  if (!o.base.empty()) {
    if (o.x.empty()) throw scenario::InputError("", std::nullopt, "--x", "", "missing; expected PARAMETER=V1,V2,...");
    study::SweepSpec spec;
    spec.source = "command line";
    spec.base = o.base;
    spec.x = study::parse_axis(o.x, "--x");
    for (const auto& s : o.series) spec.series.push_back(study::parse_axis(s, "--series"));
    spec.name = o.name.empty() ? std::filesystem::path(o.base).stem().string() + "-" + spec.x.info.name : o.name;
    spec.title = o.title.empty() ? spec.name : o.title;
    spec.replicates = o.replicates;
    spec.objects = o.objects;
    run_one(spec, o);
    return kOk;
  }
  for (const auto& f : o.files) {
    study::SweepSpec spec = study::read_sweep_file(f);
    if (o.replicates > 0) spec.replicates = o.replicates;
    if (o.objects > 0) spec.objects = o.objects;
    run_one(spec, o);
  }
  return kOk;
}

}  // namespace

Runner add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd =
      app.add_subcommand("sweep", "Parameter study over an impact case (object speed), a J232 scenario (P(pass)) or a field scenario (its hazard); CSV and SVG charts");
  cmd->add_option("files", o->files, "Sweep files (TOML); see sweeps/");
  cmd->add_option("--base", o->base, "Without a sweep file: the impact case, J232 scenario or field scenario to vary");
  cmd->add_option("--x", o->x, "The x-axis parameter and values: blade_speed=\"700 rpm,800 rpm\"");
  cmd->add_option("--series", o->series, "A series parameter (one curve per value), repeatable: restitution=0.5,0.9");
  cmd->add_option("--title", o->title, "Chart title");
  cmd->add_option("--name", o->name, "Stem of the output files");
  cmd->add_option("--out", o->out, "Output folder")->capture_default_str();
  cmd->add_option("--replicates", o->replicates, "J232 scenarios: replicates per point")->check(CLI::PositiveNumber);
  cmd->add_option("--objects", o->objects, "Field scenarios: objects per point (hazard runs)")->check(CLI::PositiveNumber);
  cmd->add_option("--threads", o->threads, "Worker threads, 0 = all cores")->check(CLI::NonNegativeNumber)->each([](const std::string& t) { warn_threads_beyond_cores(std::atoll(t.c_str())); });
  return [o] { return sweep(*o); };
}

}  // namespace j232::cli
