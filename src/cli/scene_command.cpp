// `j232 scene`: build a scenario's labelled scene and export it for a mesh viewer, or draw it
// in 3D in a page of its own (--html), with the blades' tip circles, the feed stations, the
// seat and reach envelope, and optionally the nail paths a run kept (`j232 run
// --trajectories K`).
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "assess/cluster.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "report/atomic_file.hpp"
#include "report/board_views.hpp"
#include "report/scene_view.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario.hpp"
#include "scenario/scenario_reader.hpp"
#include "scene/j232_setup.hpp"
#include "scene/markers.hpp"
#include "scene/scene.hpp"

namespace j232::cli {
namespace {
struct SceneOptions {
  std::string scenario, export_path, html_path, paths_from;
};

// The paths kept in a run's result.json of the scenario titled `title`, with what the 3D
// view shows on a click (the run's own scene.html also has each path's strikes, touches and
// way out, from a replay).
std::vector<report::ScenePath> nail_paths(const std::string& result_file, const std::string& title, const std::string& scenario_file) {
  auto refuse = [&](const std::string& expected) {
    throw scenario::InputError(result_file, std::nullopt, "--paths", result_file, expected);
  };
  std::ifstream in(result_file);
  if (!in) refuse("a result.json of `j232 run` that can be read");
  const auto j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) refuse("a result.json of `j232 run` (this is not JSON)");
  if (!j.contains("trajectories")) refuse("a result.json with nail paths: run `j232 run SCENARIO --trajectories K` first");
  std::vector<report::ScenePath> out;
  try {
    const std::string run_title = j.at("scenario").at("title").get<std::string>();
    if (run_title != title) refuse(fmt::format("a run of this scenario (\"{}\"), not of \"{}\"", title, run_title));
    for (const auto& path : j.at("trajectories").at("paths")) {
      report::ScenePath p;
      p.why = path.at("why").get<std::string>();
      p.fate = path.at("fate").get<std::string>();
      for (const auto& q : path.at("points_m")) p.points.emplace_back(q.at(0).get<double>(), q.at(1).get<double>(), q.at(2).get<double>());
      const auto replicate = path.at("replicate").get<std::uint64_t>();
      const int nail = path.at("nail").get<int>();
      p.info = {fmt::format("replicate {}, nail {} (kept: {})", replicate, nail, p.why), "fate: " + p.fate,
                fmt::format("whole trail: j232 trace {} --replicate {} --nail {}", scenario_file, replicate, nail)};
      out.push_back(std::move(p));
    }
  } catch (const nlohmann::json::exception& e) {
    refuse(fmt::format("trajectories as `j232 run --trajectories` writes them ({})", e.what()));
  }
  return out;
}

int run(const SceneOptions& o) {
  // The options first: a mistake there is reported before any work.
  if (!o.paths_from.empty() && o.export_path.empty() && o.html_path.empty())
    throw scenario::InputError("", std::nullopt, "--paths", o.paths_from,
                               "--export PATH or --html PATH too: the paths are drawn into the exported scene or the 3D view");
  if (!o.html_path.empty() && std::filesystem::path(o.html_path).extension() != ".html")
    throw scenario::InputError("", std::nullopt, "--html", o.html_path, "a file name ending in .html");
  if (!o.html_path.empty() && !report::scene_view_available())
    throw scenario::InputError("", std::nullopt, "--html", o.html_path,
                               "a build with three.js: install Debian's libjs-three (scripts/bootstrap does) and build again");
  const std::string ext = std::filesystem::path(o.export_path).extension().string();
  if (!o.export_path.empty() && ext != ".ply" && ext != ".obj")
    throw scenario::InputError("", std::nullopt, "--export", o.export_path, "a file name ending in .ply or .obj");
  const scenario::Scenario s = scenario::read_scenario(o.scenario);
  const std::vector<scene::Polyline> lines = scene::mower_markers(s);
  const std::vector<report::ScenePath> paths =
      o.paths_from.empty() ? std::vector<report::ScenePath>{} : nail_paths(o.paths_from, s.title, o.scenario);
  std::vector<scene::Polyline> exported = lines;  // the export carries the paths as lines
  for (const auto& p : paths) exported.push_back(scene::Polyline{"nail_paths", report::path_rgb(p.why), p.points, false});
  scene::Soup soup = scene::build_scene_soup(s);
  std::size_t counts[scene::kSurfaceKinds] = {};
  for (auto l : soup.labels) ++counts[static_cast<int>(l)];
  std::unique_ptr<scene::Scene> built;
  try {
    built = std::make_unique<scene::Scene>(soup);
  } catch (const std::invalid_argument& e) {
    throw scenario::InputError(s.file, std::nullopt, "meshes", "", e.what());
  }
  fmt::print("{}: {} faces\n", s.title, built->face_count());
  for (int l = 0; l < scene::kSurfaceKinds; ++l)
    if (counts[l]) fmt::print("  {:<14} {:>7} faces\n", scene::name(static_cast<scene::Surface>(l)), counts[l]);
  if (!o.export_path.empty() && assess::cluster::is_writer()) {
    report::write_atomically(o.export_path, scene::export_text(soup, exported, o.export_path));
    auto plural = [](std::size_t n) { return n == 1 ? "" : "s"; };
    fmt::print("wrote {} (the scene, {} tip circle{}, {} feed station{}{}{})\n", o.export_path, s.spindles.size(),
               plural(s.spindles.size()), s.feed_station_count(), plural(s.feed_station_count()),
               s.zone.kind == scenario::OperatorZoneSpec::Kind::Derived ? ", the seat and reach envelope" : "",
               paths.empty() ? "" : fmt::format(", {} nail paths", paths.size()));
  }
  if (!o.html_path.empty() && assess::cluster::is_writer()) {
    report::write_atomically(o.html_path, report::scene_view_html(s, soup, scene::scene_guards(s), lines, paths));
    fmt::print("wrote {} (the scene in 3D: open it in a browser; drag to turn, wheel to zoom)\n", o.html_path);
  }
  return kOk;
}
}  // namespace

Runner add_scene_command(CLI::App& app) {
  auto o = std::make_shared<SceneOptions>();
  CLI::App* cmd = app.add_subcommand("scene", "Build a scenario's labelled scene; --export writes it as PLY or OBJ, --html draws it in 3D");
  cmd->add_option("scenario", o->scenario, "Scenario file (TOML)")->required();
  cmd->add_option("--export", o->export_path,
                  "Write the labelled scene to PATH (.ply with a label and colour per face, or .obj with groups), with the blades' "
                  "tip circles, feed stations, seat and reach envelope as lines");
  cmd->add_option("--html", o->html_path,
                  "Write a page (.html, self-contained) that draws the scene in 3D with the same markers: turn, zoom and pan with "
                  "the mouse, show or hide each part and each guard from the legend");
  cmd->add_option("--paths", o->paths_from, "Add the nail paths kept in this result.json (from `j232 run --trajectories K`)");
  return [o] { return run(*o); };
}

}  // namespace j232::cli
