// `j232 calibrate`: the nail-on-blade restitution law fitted to measured impacts, or e
// from drop tests (docs/model.md §6c).
#include <fmt/format.h>

#include <memory>

#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "report/output_folder.hpp"
#include "report/atomic_file.hpp"
#include "report/calibration_files.hpp"
#include "scenario/input_error.hpp"
#include "study/calibration.hpp"
#include "study/board_calibration.hpp"
#include "report/board_fit_files.hpp"
#include "scenario/scenario_reader.hpp"
#include "projectile/projectile.hpp"
#include "report/result_files.hpp"

namespace j232::cli {
namespace {

struct CalibrateOptions {
  std::string cases, drops, board, scenario, law = "constant", out;
};

int calibrate(const CalibrateOptions& o) {
  if (static_cast<int>(!o.cases.empty()) + static_cast<int>(!o.drops.empty()) + static_cast<int>(!o.board.empty()) != 1)
    throw scenario::InputError("", std::nullopt, "calibrate", "",
                               "one of: a cases file (measured impacts), --drops FILE (drop tests of e) or --board FILE (nails onto the board)");
  if (!o.board.empty()) {
    // The nail from the scenario (the J232 test's 6d box nail unless it says otherwise).
    const auto s = scenario::read_scenario(o.scenario);
    const auto nail = projectile::Projectile::capsule(s.nail.length, s.nail.diameter, s.nail.mass);
    const auto drops = study::read_board_drops(o.board);
    const auto fit = study::fit_board(drops, nail, o.board);
    fmt::print("{}", report::board_fit_text(fit));
    fmt::print("  the scenario's board: k_p {:.1f} J/m, f_h {:.3f}, crush depth {:.1f} mm\n", s.board.puncture_energy_per_width,
               s.board.hit_fraction, 1000 * s.board.crush_depth);
    if (!o.out.empty()) {
      report::OutputFolder out(o.out, {"board.toml", "calibrate-board.json"});
      report::write_atomically(out.staged("board.toml"), report::board_fit_toml(fit));
      report::write_atomically(out.staged("calibrate-board.json"), report::json_text(report::board_fit_json(fit, drops)) + "\n");
      out.commit();
      fmt::print("Wrote {0}/board.toml (the [board] values and their ranges for j232 uq) and {0}/calibrate-board.json\n", o.out);
    }
    return kOk;
  }
  if (!o.drops.empty()) {
    const auto drops = study::read_drop_tests(o.drops);
    const auto r = study::restitution_from_drops(drops);
    fmt::print("{}", report::drop_test_table(drops, r));
    if (!o.out.empty()) {
      report::OutputFolder out(o.out, {"drop-test.json"});
      report::write_atomically(out.staged("drop-test.json"), report::json_text(report::drop_test_json(drops, r)) + "\n");
      out.commit();
      fmt::print("Wrote {}/drop-test.json\n", o.out);
    }
    return kOk;
  }
  const auto law = o.law == "power_law" ? study::LawKind::PowerLaw : study::LawKind::Constant;
  const auto cases = study::read_calibration_cases(o.cases);
  const auto r = study::calibrate(cases, law, o.cases);
  fmt::print("{}", report::calibration_table(r));
  if (!o.out.empty()) {
    report::OutputFolder out(o.out, {"calibrate.csv", "restitution.toml", "calibrate.json"});
    report::write_atomically(out.staged("calibrate.csv"), report::calibration_csv(r));
    report::write_atomically(out.staged("restitution.toml"), report::calibration_toml(r));
    report::write_atomically(out.staged("calibrate.json"), report::json_text(report::calibration_json(r)) + "\n");
    out.commit();
    fmt::print("Wrote {0}/calibrate.json, {0}/calibrate.csv and {0}/restitution.toml (the law for a scenario and for `j232 uq`)\n", o.out);
  }
  return kOk;
}

}  // namespace

Runner add_calibrate_command(CLI::App& app) {
  auto o = std::make_shared<CalibrateOptions>();
  CLI::App* cmd =
      app.add_subcommand("calibrate",
                         "Fit the nail-on-blade restitution law to measured impact speeds (least squares, intervals, held-out errors), or "
                         "find e from drop tests");
  cmd->add_option("cases", o->cases,
                  "CSV of measured impacts: columns case, scenario (an impact case file), measured_speed, and scenario keys to set per "
                  "row (see scenarios/calibration/)");
  cmd->add_option("--law", o->law, "The law to fit: constant (e) or power_law (e falls with approach speed)")
      ->check(CLI::IsMember({"constant", "power_law"}))
      ->capture_default_str();
  cmd->add_option("--drops", o->drops, "CSV of drop tests: columns drop_height, rebound_height; e = sqrt(rebound / drop height)");
  auto* board = cmd->add_option("--board", o->board,
                                "CSV of nails fired onto the board: columns speed, axis_angle (0 deg point first), result (none, hit, "
                                "puncture), optionally spin; fits the board's puncture energy, hit fraction and crush depth");
  cmd->add_option("--scenario", o->scenario, "With --board: the scenario whose nail was fired (its [nail] table)")->needs(board);
  board->needs(cmd->get_option("--scenario"));
  cmd->add_option("--out", o->out, "Also write the results into this folder (calibrate.json/.csv and restitution.toml)");
  return [o] { return calibrate(*o); };
}

}  // namespace j232::cli
