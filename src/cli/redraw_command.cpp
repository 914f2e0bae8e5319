// `j232 redraw`: a saved result's page drawn again from its JSON alone, without running
// anything: a J232 test's result.json (its compliance report), a field's hazard.json or
// compare.json (in SI or US units), a J232 comparison's compare.json, an uncertainty study's
// uq.json. Each page is drawn from the JSON as saved (report::as_saved), so the page is that
// file's by construction: `j232 run` draws its report.html the same way.
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "report/atomic_file.hpp"
#include "report/comparison_report.hpp"
#include "report/compliance_report.hpp"
#include "report/display_units.hpp"
#include "report/hazard_report.hpp"
#include "report/result_files.hpp"
#include "report/text_safety.hpp"
#include "report/uncertainty_report.hpp"
#include "scenario/input_error.hpp"

namespace j232::cli {
namespace {

using json = nlohmann::ordered_json;
using report::terminal_safe;
using scenario::InputError;

struct RedrawOptions {
  std::string file;
  std::string units = "si";
  std::string out;  // default: the page's own name beside the file
};

// What a saved file is, by the keys each writer puts first: its page's name, whether the page
// has units to choose, and how to draw it.
struct SavedKind {
  std::string page;
  bool has_units = false;
  std::string (*draw)(const json&, const report::DisplayUnits&) = nullptr;
};

SavedKind kind_of(const json& j, const std::string& file) {
  const auto text = [&](const char* key) { return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string(); };
  const std::string kind = text("kind"), program = text("program");
  if (kind == "thrown-object hazard in the field (j232 hazard)")
    return {"hazard.html", true, [](const json& r, const report::DisplayUnits& u) { return report::hazard_html(r, u); }};
  if (kind == "field designs compared (j232 compare)")
    return {"compare.html", true, [](const json& r, const report::DisplayUnits& u) { return report::hazard_comparison_html(r, u); }};
  if (program == "j232 compare") return {"compare.html", false, [](const json& r, const report::DisplayUnits&) { return report::comparison_html(r); }};
  if (program == "j232 uq") return {"uq.html", false, [](const json& r, const report::DisplayUnits&) { return report::uncertainty_html(r); }};
  if (program == "j232 run") return {"report.html", false, [](const json& r, const report::DisplayUnits&) { return report::compliance_report_html(r); }};
  throw InputError(file, std::nullopt, kind.empty() ? "program" : "kind", kind.empty() ? program : kind,
                   "expected a result.json, hazard.json, compare.json or uq.json as j232 run, hazard, compare or uq writes it");
}

int redraw(const RedrawOptions& o) {
  const report::DisplayUnits units = report::display_units(o.units);  // (a bad name refused before anything is read)
  std::ifstream in(o.file, std::ios::binary);
  if (!in) throw InputError::file_problem(o.file, std::nullopt, "cannot be read (expected a result.json, hazard.json, compare.json or uq.json that j232 wrote)");
  std::stringstream text;
  text << in.rdbuf();
  const json j = json::parse(text.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw InputError::file_problem(o.file, std::nullopt, "not JSON as j232 writes it (expected an object)");
  const SavedKind k = kind_of(j, o.file);
  if (units.us && !k.has_units)
    throw InputError(o.file, std::nullopt, "--units", o.units, fmt::format("expected si: {} gives shares and probabilities, which have no units", k.page));
  std::string page;
  try {
    page = k.draw(report::as_saved(j), units);
  } catch (const nlohmann::json::exception& e) {
    // A file written by another version, or edited: name what the page needed.
    throw InputError::file_problem(o.file, std::nullopt,
                                   fmt::format("lacks what {} draws, as this version of j232 writes it ({})", k.page, e.what()));
  } catch (const std::out_of_range& e) {  // (a list shorter than another it goes with, a value out of its range)
    throw InputError::file_problem(o.file, std::nullopt,
                                   fmt::format("holds what {} cannot draw, as this version of j232 writes it ({})", k.page, e.what()));
  }
  // Beside the file by default: the page itself in SI, a page of its own in US units (the
  // SI page stays, as the JSON and CSV beside it are SI).
  std::string page_name = k.page;
  if (units.us) page_name.insert(page_name.size() - 5, "-us");
  const std::string out = o.out.empty() ? (std::filesystem::path(o.file).parent_path() / page_name).string() : o.out;
  report::write_atomically(out, page);
  fmt::print("Wrote {} from {}\n", terminal_safe(out), terminal_safe(o.file));
  return kOk;
}

}  // namespace

Runner add_redraw_command(CLI::App& app) {
  auto o = std::make_shared<RedrawOptions>();
  CLI::App* cmd = app.add_subcommand(
      "redraw", "Draw a saved result's page again from its JSON alone, running nothing (a field's page in other units, say)");
  cmd->add_option("file", o->file, "A result.json, hazard.json, compare.json or uq.json that j232 wrote")->required();
  cmd->add_option("--units", o->units,
                  "Units of a field's page (hazard.json, a field's compare.json): si (m, m/s, J, per km) or us (ft, mph, ft-lb, per mile)")
      ->capture_default_str();
  cmd->add_option("--out", o->out,
                  "The page to write (default: report.html, hazard.html, compare.html or uq.html beside the file; hazard-us.html or compare-us.html in US units)");
  return [o] { return redraw(*o); };
}

}  // namespace j232::cli
