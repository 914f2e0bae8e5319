// `j232 impact`: one blade-object impact, the report's second program (Appendix A).
#include <cstdio>
#include <fmt/format.h>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "blade/blade_model.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "report/impact_report.hpp"
#include "scenario/impact_input.hpp"
#include "scenario/toml_override.hpp"
#include "scenario/toml_reader.hpp"
#include "report/result_files.hpp"

namespace j232::cli {
namespace {

struct ImpactOptions {
  std::string scenario;
  bool json = false;
  std::vector<std::string> assignments;  // KEY=VALUE, applied over the file
  // Named shortcuts for the common keys.
  std::string speed, e, contact_radius, object_mass, object_speed, blade_mass, blade_length;
};

int run_impact(const ImpactOptions& o) {
  toml::table doc;
  std::string source = "command line";
  if (!o.scenario.empty()) {
    doc = scenario::parse_toml_file(o.scenario);
    source = o.scenario;
  }
  std::vector<std::string> sets;
  if (!o.blade_mass.empty() || !o.blade_length.empty()) {
    // The report's own model: one straight rod turning about its end.
    sets.push_back("blade.hub.bar_mount=end");
    if (!o.blade_mass.empty()) sets.push_back("blade.hub.bar_mass=" + o.blade_mass);
    if (!o.blade_length.empty()) sets.push_back("blade.hub.bar_length=" + o.blade_length);
  }
  auto shortcut = [&](const std::string& value, const char* key) {
    if (!value.empty()) sets.push_back(std::string(key) + "=" + value);
  };
  shortcut(o.speed, "blade.speed");
  shortcut(o.e, "restitution.e");
  shortcut(o.contact_radius, "contact.radius");
  shortcut(o.object_mass, "object.mass");
  shortcut(o.object_speed, "object.speed_toward_blade");
  sets.insert(sets.end(), o.assignments.begin(), o.assignments.end());
  for (const auto& s : sets) scenario::assign(doc, s);

  const scenario::ImpactCase input = scenario::read_impact_case(doc, source);
  std::unique_ptr<blade::BladeModel> model;
  try {
    model = std::make_unique<blade::BladeModel>(input.blade);
  } catch (const std::invalid_argument& e) {
    throw scenario::InputError(source, std::nullopt, "blade", "", e.what());
  }
  blade::ImpactSolution solution;
  try {
    solution = blade::solve_impact(*model, input.location, input.object, input.restitution);
  } catch (const std::invalid_argument& e) {
    throw scenario::InputError(source, std::nullopt, "object", "", e.what());
  }
  if (o.json)
    fmt::print("{}\n", report::json_text(report::impact_json(input, solution)));
  else
    fmt::print("{}", report::impact_table(input, solution));
  return kOk;
}

}  // namespace

Runner add_impact_command(CLI::App& app) {
  auto options = std::make_shared<ImpactOptions>();
  CLI::App* cmd =
      app.add_subcommand("impact", "Compute one blade-object impact (report 445-1, Appendix A) from a scenario file and/or options");
  cmd->add_option("scenario", options->scenario, "Impact scenario file (TOML); see scenarios/impact/");
  cmd->add_flag("--json", options->json, "Print JSON (SI units, plus ft/min for object speeds) instead of a table");
  cmd->add_option("--set", options->assignments, "Override any key: --set blade.speed=\"900 rpm\"")->type_name("KEY=VALUE");
  cmd->add_option("--speed", options->speed, "Blade speed, e.g. \"1000 rpm\"");
  cmd->add_option("--e", options->e, "Coefficient of restitution, 0 to 1");
  cmd->add_option("--contact-radius", options->contact_radius, "Contact radius from the spindle, e.g. \"22 in\"");
  cmd->add_option("--object-mass", options->object_mass, "Object mass, e.g. \"2 g\"");
  cmd->add_option("--object-speed", options->object_speed, "Object speed toward the blade, e.g. \"440 ft/min\"");
  cmd->add_option("--blade-mass", options->blade_mass, "Straight blade (one rod about its end): mass, e.g. \"22 lb\"");
  cmd->add_option("--blade-length", options->blade_length, "Straight blade: length from the spindle, e.g. \"2 ft\"");
  return [options] { return run_impact(*options); };
}

}  // namespace j232::cli
