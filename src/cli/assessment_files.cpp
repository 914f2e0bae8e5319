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
#include <unistd.h>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "report/atomic_file.hpp"
#include "report/compliance_report.hpp"
#include "report/result_files.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario.hpp"
#include "scene/j232_setup.hpp"

#ifndef J232_GIT_REVISION
#define J232_GIT_REVISION "unknown"
#endif

namespace j232::cli {
namespace {

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
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

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

// FNV-1a, 64 bit: a change detector for --resume, not a security hash.
struct Fnv {
  std::uint64_t h = 1469598103934665603ULL;
  void add(std::string_view bytes) {
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ULL;
    add_separator();
  }
  void add_separator() { h = (h ^ 0xffu) * 1099511628211ULL; }
};

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string digest(const std::string& scenario_file, const std::vector<scenario::MeshFile>& meshes, const RunOverrides& o) {
  Fnv f;
  f.add(file_bytes(scenario_file));
  for (const auto& m : meshes) f.add(file_bytes(m.path));
  // Not the thread count: results do not depend on it.
  f.add(fmt::format("{} {} {} {}", o.replicates, o.seed, J232_VERSION, J232_GIT_REVISION));
  return fmt::format("{:016x}", f.h);
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
  std::filesystem::create_directories(out, ec);
  if (ec) throw scenario::InputError("", std::nullopt, "--out", out, "cannot create the output folder: " + ec.message());
  const report::Provenance p{J232_VERSION, J232_GIT_REVISION, utc_now(), digest(scenario_file, s.meshes, o), a.threads, a.wall_seconds};
  RunOutcome outcome{report::result_json(s, a, sum, p), report::summary_text(s, sum)};
  const std::filesystem::path dir(out);
  report::write_atomically((dir / "marks.csv").string(), report::marks_csv(a));
  report::write_atomically((dir / "report.html").string(),
                           report::compliance_report_html(s, a, sum, outcome.result, scene::build_scene_soup(s)));
  report::write_atomically((dir / "result.json").string(), outcome.result.dump(2) + "\n");  // last: marks completeness
  return outcome;
}

}  // namespace j232::cli
