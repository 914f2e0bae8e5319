// Reading a sweep: the sweep file (study/sweep.hpp gives its form) and --x/--series axes.
#include <filesystem>
#include <fmt/format.h>
#include <set>

#include "scenario/input_error.hpp"
#include "scenario/toml_reader.hpp"
#include "study/sweep.hpp"

namespace j232::study {

namespace {

using scenario::InputError;

std::optional<int> line_of(const toml::node& n) {
  return n.source().begin.line > 0 ? std::optional<int>(static_cast<int>(n.source().begin.line)) : std::nullopt;
}

std::string value_text(const toml::node& n) {
  if (auto s = n.value<std::string>()) return *s;
  if (n.is_integer()) return fmt::format("{}", *n.value<long long>());
  if (n.is_floating_point()) return fmt::format("{}", *n.value<double>());
  if (auto b = n.value<bool>()) return *b ? "true" : "false";
  return "";
}

void refuse_unknown(const toml::table& t, const std::set<std::string>& known, const std::string& file, const std::string& path) {
  for (const auto& [k, v] : t)
    if (!known.count(std::string(k.str())))
      throw InputError(file, line_of(v), path + std::string(k.str()), value_text(v),
                       fmt::format("unknown key; this table takes: {}", fmt::join(known, ", ")));
}

Axis read_axis(const toml::table& t, const std::string& file, const std::string& path) {
  refuse_unknown(t, {"parameter", "values", "from", "to", "steps"}, file, path);
  const auto* p = t.get("parameter");
  if (!p || !p->is_string())
    throw InputError(file, line_of(t), path + "parameter", "",
                     "missing; expected a parameter name (blade_speed, blade_mass, restitution, contact_radius, "
                     "pivot_position, object_mass, object_speed) or a dotted key of the base file");
  Axis axis{parameter_info(*p->value<std::string>()), {}};
  if (const auto* values = t.get_as<toml::array>("values")) {
    if (t.contains("from")) throw InputError(file, line_of(t), path + "from", "", "expected either values or from/to/steps, not both");
    for (const auto& v : *values) {
      const std::string text = value_text(v);
      if (text.empty()) throw InputError(file, line_of(v), path + "values", "", "expected numbers or quantities such as \"700 rpm\"");
      axis.values.push_back(make_setting(axis.info, text, file, line_of(v), path + "values"));
    }
  } else if (t.contains("from") || t.contains("to")) {
    const std::string from = t.contains("from") ? value_text(*t.get("from")) : "", to = t.contains("to") ? value_text(*t.get("to")) : "";
    const auto* steps_node = t.get("steps");
    const long long steps = steps_node ? steps_node->value<long long>().value_or(0) : 0;
    if (steps < 2 || steps > 1000)
      throw InputError(file, steps_node ? line_of(*steps_node) : line_of(t), path + "steps", steps_node ? value_text(*steps_node) : "",
                       "expected an integer number of points from 2 to 1000");
    const Setting a = make_setting(axis.info, from, file, line_of(*t.get("from")), path + "from");
    const Setting b = make_setting(axis.info, to, file, line_of(*t.get("to")), path + "to");
    // Points evenly spaced, written in the unit `from` was written in.
    const auto space = from.find(' ');
    const std::string unit = space == std::string::npos ? "" : from.substr(space);
    const double per_unit = a.si / std::stod(from);
    for (long long i = 0; i < steps; ++i) {
      const double si = a.si + (b.si - a.si) * static_cast<double>(i) / static_cast<double>(steps - 1);
      axis.values.push_back(make_setting(axis.info, fmt::format("{:.6g}{}", si / per_unit, unit), file, line_of(t), path + "from"));
      axis.values.back().si = si;  // exact, not as rounded for the label
    }
  } else {
    throw InputError(file, line_of(t), path + "values", "", "missing; expected values = [...] or from, to and steps");
  }
  if (axis.values.empty()) throw InputError(file, line_of(t), path + "values", "[]", "expected at least one value");
  axis.info = axis.values.front().info;  // a file key's axis title names the unit its values were given in
  return axis;
}

}  // namespace

SweepSpec read_sweep_file(const std::string& file) {
  const toml::table doc = scenario::parse_toml_file(file);
  refuse_unknown(doc, {"title", "base", "set", "x", "series", "run"}, file, "");
  SweepSpec spec;
  spec.source = file;
  spec.name = std::filesystem::path(file).stem().string();
  spec.title = doc["title"].value_or(spec.name);
  const auto base = doc["base"].value<std::string>();
  if (!base)
    throw InputError(file, line_of(doc), "base", "", "missing; expected the impact case or J232 scenario to vary, relative to this file");
  spec.base = (std::filesystem::path(file).parent_path() / *base).lexically_normal().string();
  if (const auto* set = doc.get("set")) {
    if (!set->is_table()) throw InputError(file, line_of(*set), "set", "", "expected a [set] table of parameter = value");
    for (const auto& [k, v] : *set->as_table()) {
      const std::string text = value_text(v);
      if (text.empty()) throw InputError(file, line_of(v), "set." + std::string(k.str()), "", "expected a number or quantity");
      spec.fixed.push_back(make_setting(parameter_info(std::string(k.str())), text, file, line_of(v), "set." + std::string(k.str())));
    }
  }
  const auto* x = doc.get_as<toml::table>("x");
  if (!x) throw InputError(file, line_of(doc), "x", "", "missing; expected an [x] table: parameter and values");
  spec.x = read_axis(*x, file, "x.");
  if (const auto* series = doc.get("series")) {
    const auto* list = series->as_array();
    if (!list || !list->is_array_of_tables())
      throw InputError(file, line_of(*series), "series", "", "expected [[series]] tables: parameter and values");
    for (std::size_t i = 0; i < list->size(); ++i)
      spec.series.push_back(read_axis(*list->get(i)->as_table(), file, fmt::format("series[{}].", i + 1)));
  }
  if (const auto* run = doc.get_as<toml::table>("run")) {
    refuse_unknown(*run, {"replicates", "objects", "seed"}, file, "run.");
    if (const auto* r = run->get("objects")) {
      spec.objects = r->value<long long>().value_or(0);
      if (spec.objects <= 0) throw InputError(file, line_of(*r), "run.objects", value_text(*r), "expected a positive integer");
    }
    if (const auto* r = run->get("replicates")) {
      spec.replicates = r->value<long long>().value_or(0);
      if (spec.replicates <= 0) throw InputError(file, line_of(*r), "run.replicates", value_text(*r), "expected a positive integer");
    }
    if (const auto* s = run->get("seed")) {
      const long long seed = s->value<long long>().value_or(-1);
      if (seed < 0) throw InputError(file, line_of(*s), "run.seed", value_text(*s), "expected a non-negative integer");
      spec.seed = static_cast<unsigned long long>(seed);
    }
  }
  return spec;
}

Axis parse_axis(const std::string& text, const std::string& option) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InputError("", std::nullopt, option, text, "expected PARAMETER=V1,V2,... for example blade_speed=\"700 rpm,800 rpm\"");
  Axis axis{parameter_info(text.substr(0, eq)), {}};
  std::size_t start = eq + 1;
  while (start <= text.size()) {
    std::size_t comma = text.find(',', start);
    if (comma == std::string::npos) comma = text.size();
    std::string v = text.substr(start, comma - start);
    v.erase(0, v.find_first_not_of(' '));
    v.erase(v.find_last_not_of(' ') + 1);
    if (!v.empty()) axis.values.push_back(make_setting(axis.info, v, "", std::nullopt, option));
    start = comma + 1;
  }
  if (axis.values.empty()) throw InputError("", std::nullopt, option, text, "expected at least one value");
  axis.info = axis.values.front().info;
  return axis;
}

}  // namespace j232::study
