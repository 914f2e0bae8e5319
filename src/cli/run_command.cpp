// `j232 run`: the J232 assessment of one scenario, from file to verdict.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <thread>
#include <unistd.h>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "report/atomic_file.hpp"
#include "report/result_files.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario.hpp"

#ifndef J232_GIT_REVISION
#define J232_GIT_REVISION "unknown"
#endif

namespace j232::cli {
namespace {

struct RunOptions {
  std::string scenario;
  std::string out = "results";
  long long replicates = 0;
  long long seed = -1;
  int threads = -1;
};

// A progress bar on stderr, redrawn from its own thread, only on a terminal.
class ProgressBar {
 public:
  explicit ProgressBar(assess::Progress& p) : progress_(p), on_(isatty(fileno(stderr)) != 0) {
    if (on_) thread_ = std::thread([this] { loop(); });
  }
  ~ProgressBar() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    if (on_) std::fprintf(stderr, "\r%70s\r", "");
  }

 private:
  void loop() {
    const auto start = std::chrono::steady_clock::now();
    while (!stop_) {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      const long long done = progress_.done, total = std::max(1LL, progress_.total.load());
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double frac = std::min(1.0, static_cast<double>(done) / total);
      const int width = 30, filled = static_cast<int>(frac * width);
      const double eta = done > 0 ? elapsed * (total - done) / done : 0;
      std::fprintf(stderr, "\r[%s%s] %3.0f%%  %lld/%lld replicates  %.1f s  ETA %.0f s ", std::string(filled, '#').c_str(),
                   std::string(width - filled, ' ').c_str(), 100 * frac, done, total, elapsed, eta);
      std::fflush(stderr);
    }
  }
  assess::Progress& progress_;
  bool on_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

int run(const RunOptions& o) {
  scenario::Scenario s = scenario::read_scenario(o.scenario);
  if (o.replicates > 0) s.run.replicates = o.replicates;
  if (o.seed >= 0) s.run.seed = static_cast<unsigned long long>(o.seed);
  if (o.threads >= 0) s.run.threads = o.threads;

  const assess::Simulator simulator(s);
  assess::Progress progress;
  assess::Assessment a;
  {
    ProgressBar bar(progress);
    a = assess::run_assessment(simulator, s.run.threads, &progress);
  }
  const assess::Summary sum = assess::summarise(a, s.criteria);

  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) throw scenario::InputError("", std::nullopt, "--out", o.out, "cannot create the output folder: " + ec.message());
  const report::Provenance p{J232_VERSION, J232_GIT_REVISION, utc_now(), a.threads, a.wall_seconds};
  report::write_atomically((std::filesystem::path(o.out) / "marks.csv").string(), report::marks_csv(a));
  report::write_atomically((std::filesystem::path(o.out) / "result.json").string(),
                           report::result_json(s, a, sum, p).dump(2) + "\n");
  fmt::print("{}", report::summary_text(s, sum));
  fmt::print("  {:.2f} s on {} thread(s): {:.0f} nails/s.  Wrote {}/result.json and {}/marks.csv\n", a.wall_seconds,
             a.threads, a.wall_seconds > 0 ? a.nails / a.wall_seconds : 0.0, o.out, o.out);
  return sum.passes ? kOk : kFails;
}

}  // namespace

Runner add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Simulate the SAE J232 test of a scenario and judge it (exit 0 passes, 1 fails)");
  cmd->add_option("scenario", o->scenario, "Scenario file (TOML); see scenarios/")->required();
  cmd->add_option("--replicates", o->replicates, "Replicates of the whole test (overrides [run] replicates)")->check(CLI::PositiveNumber);
  cmd->add_option("--seed", o->seed, "Random seed (overrides [run] seed)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--threads", o->threads, "Worker threads, 0 = all cores (overrides [run] threads)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", o->out, "Output folder for result.json and marks.csv")->capture_default_str();
  return [o] { return run(*o); };
}

}  // namespace j232::cli
