// j232: Monte Carlo assessor for the SAE J232 thrown-object test.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <fmt/format.h>

#include "assess/cluster.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "report/atomic_file.hpp"
#include "report/text_safety.hpp"
#include "scenario/input_error.hpp"
#include "j232/version.hpp"

namespace {
int run_command_line(int argc, char** argv) {
  using namespace j232::cli;
  namespace cluster = j232::assess::cluster;
  // In an MPI job every rank runs the command; rank 0 reports input errors (every rank sees
  // the same input), any rank reports what only it met.
  const bool reporter = cluster::is_writer();
  using j232::report::terminal_safe;
  CLI::App app{std::string("j232 ") + j232::version + " — simulates the SAE J232 thrown-object test of rotary mowers"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("j232 ") + j232::version);
  const Runner impact = add_impact_command(app);
  const Runner run = add_run_command(app);
  const Runner scene = add_scene_command(app);
  const Runner batch = add_batch_command(app);
  const Runner sweep = add_sweep_command(app);
  const Runner compare = add_compare_command(app);
  const Runner uq = add_uq_command(app);
  const Runner calibrate = add_calibrate_command(app);
  const Runner trace = add_trace_command(app);
  const Runner hazard = add_hazard_command(app);
  const Runner redraw = add_redraw_command(app);
  // An unknown first word is named as such (CLI11 would say only that a subcommand is required).
  if (argc > 1 && argv[1][0] != '-' && app.get_subcommands([&](const CLI::App* c) { return c->get_name() == argv[1]; }).empty()) {
    if (reporter)
      fmt::print(stderr, "j232: error: unknown command \"{}\"; expected one of impact, run, scene, batch, sweep, compare, uq, calibrate, "
                         "trace, hazard, redraw (j232 --help)\n",
                 terminal_safe(argv[1]));
    return kBadInput;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = reporter ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 1);
    return code == 0 ? kOk : kBadInput;
  }
  try {
    if (app.got_subcommand("impact")) return impact();
    if (app.got_subcommand("run")) return run();
    if (app.got_subcommand("scene")) return scene();
    if (app.got_subcommand("batch")) return batch();
    if (app.got_subcommand("sweep")) return sweep();
    if (app.got_subcommand("compare")) return compare();
    if (app.got_subcommand("uq")) return uq();
    if (app.got_subcommand("calibrate")) return calibrate();
    if (app.got_subcommand("trace")) return trace();
    if (app.got_subcommand("hazard")) return hazard();
    if (app.got_subcommand("redraw")) return redraw();
  } catch (const j232::scenario::InputError& e) {
    if (reporter) fmt::print(stderr, "j232: error: {}\n", terminal_safe(e.what()));
    return kBadInput;
  } catch (const j232::report::FileError& e) {
    if (reporter) fmt::print(stderr, "j232: error: {}\n", terminal_safe(e.what()));
    return kBadInput;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "j232{}: error: out of memory; reduce the scene (mesh sizes) or the replicates\n",
               reporter ? "" : fmt::format(" (rank {})", cluster::rank()));
    return kBadInput;
  } catch (const std::exception& e) {
    fmt::print(stderr, "j232{}: internal error: {}\n(please report this with the input that caused it)\n",
               reporter ? "" : fmt::format(" (rank {})", cluster::rank()), terminal_safe(e.what()));
    return kInternal;
  }
  return kInternal;
}
}  // namespace

int main(int argc, char** argv) {
  namespace cluster = j232::assess::cluster;
  cluster::init(&argc, &argv);
  // Rank 0 alone prints results; the others stay quiet but for errors of their own.
  if (!cluster::is_writer() && !std::freopen("/dev/null", "w", stdout)) return j232::cli::kInternal;
  const int code = run_command_line(argc, argv);
  // A failure anywhere ends every rank now: none may wait for ever for a partner that left,
  // and no rank writes a partial result (rank 0 writes only at the end of a command).
  if (code != j232::cli::kOk && cluster::size() > 1 && code != j232::cli::kFails && code != j232::cli::kInvalid) {
    std::fflush(stdout), std::fflush(stderr);
    cluster::abort(code);
  }
  cluster::finalize();
  return code;
}
