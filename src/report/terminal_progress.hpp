#pragma once
// Progress on a terminal: a bar for one assessment, a step counter for studies. Both draw
// on stderr only when it is a terminal, so piped output and notebooks stay clean.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <fmt/format.h>
#include <cstdio>
#include <string>
#include <thread>
#include <unistd.h>

#include "assess/runner.hpp"

namespace j232::report {

// "LABEL i of n" on stderr, only on a terminal, rewritten in place at each step and cleared
// at the end (studies that count whole assessments: j232 uq, run --uncertainty).
class StepCounter {
 public:
  explicit StepCounter(const char* label) : label_(label), on_(isatty(fileno(stderr)) != 0) {}
  ~StepCounter() {
    if (on_) std::fprintf(stderr, "\r%100s\r", "");
  }
  StepCounter(const StepCounter&) = delete;
  StepCounter& operator=(const StepCounter&) = delete;
  void operator()(std::size_t i, std::size_t n) const {
    if (on_) std::fprintf(stderr, "\r%s %zu of %zu ", label_, i + 1, n);
  }

 private:
  const char* label_;
  bool on_;
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
    if (on_) std::fprintf(stderr, "\r%100s\r", "");
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
      const double frac = std::min(1.0, static_cast<double>(done) / static_cast<double>(total));
      const int width = 30, filled = static_cast<int>(frac * width);
      const double eta = done > 0 ? elapsed * static_cast<double>(total - done) / static_cast<double>(done) : 0;
      // With a stop rule the bar is the batch under way, after the looks that did not stop it.
      const int looks = progress_.looks;
      std::fprintf(stderr, "\r[%s%s] %3.0f%%  %lld/%lld replicates  %.1f s  ETA %.0f s%s ", std::string(filled, '#').c_str(),
                   std::string(width - filled, ' ').c_str(), 100 * frac, done, total, elapsed, eta,
                   looks > 0 ? fmt::format(" (batch {} of a stop rule)", looks + 1).c_str() : "");
      std::fflush(stderr);
    }
  }
  assess::Progress& progress_;
  bool on_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace j232::report
