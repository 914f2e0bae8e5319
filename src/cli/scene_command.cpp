// `j232 scene`: build a scenario's labelled scene and export it for a mesh viewer.
#include <fmt/format.h>
#include <memory>

#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario.hpp"
#include "scene/j232_setup.hpp"
#include "scene/scene.hpp"

namespace j232::cli {
namespace {
struct SceneOptions {
  std::string scenario, export_path;
};

int run(const SceneOptions& o) {
  const scenario::Scenario s = scenario::read_scenario(o.scenario);
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
  if (!o.export_path.empty()) {
    try {
      scene::export_scene(soup, o.export_path);
    } catch (const std::exception& e) {
      throw scenario::InputError("", std::nullopt, "--export", o.export_path, e.what());
    }
    fmt::print("wrote {}\n", o.export_path);
  }
  return kOk;
}
}  // namespace

Runner add_scene_command(CLI::App& app) {
  auto o = std::make_shared<SceneOptions>();
  CLI::App* cmd = app.add_subcommand("scene", "Build a scenario's labelled scene; --export writes it as PLY or OBJ");
  cmd->add_option("scenario", o->scenario, "Scenario file (TOML)")->required();
  cmd->add_option("--export", o->export_path, "Write the labelled scene to PATH (.ply with a label and colour per face, or .obj with groups)");
  return [o] { return run(*o); };
}

}  // namespace j232::cli
