// j232_bench: how fast the assessment runs, and where the time goes.
//
//   build/j232_bench [SCENARIO...] [--replicates N]
//
// Without a scenario it measures the report's highway mower (scenarios/highway-pivoted.toml)
// and the three-spindle deck (scenarios/deck-72in-three-spindle.toml). For each, and for
// each scene engine built in (CGAL's AABB tree, Embree's BVH; --engine picks one):
// simulated nails per second on 1 and on 2 threads (median of 3 runs each) and the wall
// time of the full assessment; the mean number of scene queries per nail; the events a struck
// nail's flight takes (bounces, gentle contacts, those on walls, blade strikes); and the raw
// query rate on the same scene with chords like the nails' (ns per query), so the cost of
// everything beyond the queries is visible.
//
//   build/j232_bench --uq [N]
//
// times the raised-skirt mower's uncertainty study (j232's default inputs) at N base draws
// (default 256, the study's default) of 50 replicates on 2 threads: seconds in all, per
// assessment, and nails per second.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <cstdio>
#include <cstring>
#include <string>
#include <sys/resource.h>
#include <vector>

#include "assess/runner.hpp"
#include "random/stream.hpp"
#include "scene/j232_setup.hpp"
#include "scenario/scenario_reader.hpp"
#include "scenario/toml_override.hpp"
#include "scenario/toml_reader.hpp"
#include "study/uncertainty.hpp"

using namespace j232;
using Clock = std::chrono::steady_clock;

static double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

static void bench(const std::string& path, long long replicates, const std::vector<scene::Engine>& engines);
static void bench_uq(long long base_draws);

int main(int argc, char** argv) {
  std::vector<std::string> paths;
  long long replicates = 3000;
  std::string engine_choice = "both";
  long long uq_draws = 0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      std::printf(
          "usage: j232_bench [SCENARIO...] [--replicates N] [--engine cgal|embree|both]\n"
          "       j232_bench --uq [N]   (the raised-skirt uncertainty study at N base draws, default 256)\n"
          "  defaults: highway-pivoted and the three-spindle deck, 3000 replicates, every engine built in\n");
      return 0;
    }
    if (!std::strcmp(argv[i], "--uq")) {
      uq_draws = 256;
      if (i + 1 < argc && std::atoll(argv[i + 1]) > 0) uq_draws = std::atoll(argv[++i]);
    } else if (!std::strcmp(argv[i], "--replicates") && i + 1 < argc) {
      replicates = std::atoll(argv[++i]);
    } else if (!std::strcmp(argv[i], "--engine") && i + 1 < argc) {
      const std::string e = argv[++i];
      if (e != "cgal" && e != "embree" && e != "both") {
        std::fprintf(stderr, "j232_bench: --engine expects cgal, embree or both, not %s\n", e.c_str());
        return 2;
      }
      engine_choice = e;
    } else {
      paths.emplace_back(argv[i]);
    }
  }
  std::vector<scene::Engine> engines;
  for (auto e : {scene::Engine::Cgal, scene::Engine::Embree})
    if ((engine_choice == "both" || engine_choice == scene::engine_name(e)) && scene::engine_available(e)) engines.push_back(e);
  if (engines.empty()) {
    std::fprintf(stderr, "j232_bench: the %s engine is not built in\n", engine_choice.c_str());
    return 2;
  }
  if (replicates < 1) {
    std::fprintf(stderr, "j232_bench: --replicates expects a positive number\n");
    return 2;
  }
  if (uq_draws > 0) {
    try {
      bench_uq(uq_draws);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "j232_bench: %s\n", e.what());
      return 2;
    }
    return 0;
  }
  if (paths.empty())
    for (const char* name : {"highway-pivoted.toml", "deck-72in-three-spindle.toml"})
      paths.push_back(std::string(J232_SOURCE_DIR) + "/scenarios/" + name);
  try {
    for (const auto& p : paths) bench(p, replicates, engines);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "j232_bench: %s\n", e.what());
    return 2;
  }
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("peak resident memory: %.0f MB\n", static_cast<double>(usage.ru_maxrss) / 1024.0);
  return 0;
}

static void bench(const std::string& path, long long replicates, const std::vector<scene::Engine>& engines) {
  auto s = scenario::read_scenario(path);
  s.run.replicates = replicates;
  s.run.target_half_width.reset();
  std::printf("j232_bench: %s\n  %lld replicates x %d nails = %lld nails per run\n", s.title.c_str(), replicates, s.feed.nails,
              replicates * s.feed.nails);
  std::vector<double> two_thread_rates;
  for (const scene::Engine engine : engines) {
    const auto built = Clock::now();
    const assess::Simulator sim(s, engine);
    const double build_seconds = std::chrono::duration<double>(Clock::now() - built).count();
    std::printf("  engine %s (scene built in %.3f s):\n", scene::engine_name(engine), build_seconds);
    double queries_per_nail = 0;
    struct Events {
      double bounces = 0, gentle = 0, walls = 0, strikes = 0;  // per struck nail
    } events;
    for (int threads : {1, 2}) {
      std::vector<double> rates, walls;
      for (int rep = 0; rep < 3; ++rep) {
        const auto a = assess::run_assessment(sim, threads);
        rates.push_back(static_cast<double>(a.nails) / a.wall_seconds);
        walls.push_back(a.wall_seconds);
        queries_per_nail = static_cast<double>(a.queries) / static_cast<double>(a.nails);
        const double struck = static_cast<double>(std::max<std::uint64_t>(a.struck, 1));
        events = {static_cast<double>(a.bounces) / struck, static_cast<double>(a.gentle_contacts) / struck,
                  static_cast<double>(a.wall_contacts) / struck, a.strikes.mean()};
      }
      std::printf("    %d thread%s: %10.0f nails/s (median of 3; %.2f s per full assessment)\n", threads, threads == 1 ? " " : "s",
                  median(rates), median(walls));
      if (threads == 2) two_thread_rates.push_back(median(rates));
    }
    std::printf("    scene queries per nail: %.2f\n", queries_per_nail);
    // What a nail's flight spends its events on (the cost is in their number: docs/validation.md §4).
    std::printf("    events per struck nail: %.2f bounces, %.2f gentle contacts (%.2f of either on walls), %.2f blade strikes\n",
                events.bounces, events.gentle, events.walls, events.strikes);

    // Raw query rate: chords of 0.3 m from random points under the deck in random directions.
    const auto& scene = sim.scene();
    const int n = 2'000'000;
    random::Stream rng(1, 0, 0, random::Purpose::Test);
    std::vector<scene::Vec3> from(1024), dir(1024);
    for (std::size_t i = 0; i < from.size(); ++i) {
      const double r = 0.6 * std::sqrt(rng.uniform()), a = 6.283185307179586 * rng.uniform();
      from[i] = {s.spindles[i % s.spindles.size()].x + r * std::cos(a), s.spindles[i % s.spindles.size()].y + r * std::sin(a),
                 0.02 + 0.15 * rng.uniform()};
      scene::Vec3 d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      dir[i] = d.normalized();
    }
    const auto t0 = Clock::now();
    long hits = 0;
    for (int i = 0; i < n; ++i) hits += scene.first_hit(from[i & 1023], dir[i & 1023], 0.3).has_value();
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    const double rate = n / seconds;
    std::printf("    raw queries (0.3 m chords, 1 thread): %.0f queries/s, %.0f ns per query (%.0f%% hit), %zu faces\n", rate, 1e9 / rate,
                100.0 * static_cast<double>(hits) / static_cast<double>(n), scene.face_count());
    std::printf("    so queries alone would allow %.0f nails/s on 1 thread\n", rate / queries_per_nail);
  }
  if (two_thread_rates.size() == 2) std::printf("  embree / cgal, 2 threads: %.2fx\n", two_thread_rates[1] / two_thread_rates[0]);
}

static void bench_uq(long long base_draws) {
  const std::string source = std::string(J232_SOURCE_DIR) + "/scenarios/highway-pivoted-raised-skirt.toml";
  toml::table doc = scenario::parse_toml_file(source);
  scenario::set_key(doc, "uncertainty.base_draws", std::to_string(base_draws), "j232_bench");
  scenario::set_key(doc, "uncertainty.replicates", "50", "j232_bench");
  const auto file = std::filesystem::temp_directory_path() / "j232_bench_uq.toml";
  std::ofstream(file) << doc << "\n";
  const auto start = Clock::now();
  const auto r = study::run_uncertainty(file.string(), 2);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::filesystem::remove(file);
  const double nails = static_cast<double>(r.outputs.size()) * 50.0 * 150.0;
  std::printf("j232_bench --uq: %s\n  %zu inputs, %lld base draws, %zu assessments of 50 replicates on 2 threads: %.1f s (%.3f s per "
              "assessment, %.0f nails/s)\n",
              r.title.c_str(), r.plan.inputs.size(), base_draws, r.outputs.size(), seconds, seconds / static_cast<double>(r.outputs.size()),
              nails / seconds);
}
