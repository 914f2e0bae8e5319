#include "scenario/toml_override.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <optional>

#include "scenario/input_error.hpp"

namespace j232::scenario {

namespace {

// The value parsed with `origin` as its source path, so an error about it names where it
// came from (the readers tell it from the file's own values by that path).
void put(toml::table& table, const std::string& leaf, const std::string& value, const std::string& origin) {
  try {
    toml::table parsed = toml::parse("v = " + value, origin);
    table.insert_or_assign(leaf, std::move(*parsed.get("v")));
  } catch (const toml::parse_error&) {
    // Not a TOML value: the text as a string (a TOML basic string, escaped as JSON escapes it).
    toml::table parsed = toml::parse("v = " + nlohmann::json(value).dump(-1, ' ', true), origin);
    table.insert_or_assign(leaf, std::move(*parsed.get("v")));
  }
}

// Sets the part of `full` from `start` on inside `table` (into every table of an array of tables).
void set_in(toml::table& table, std::size_t start, const std::string& full, const std::string& value, const std::string& origin) {
  const std::size_t dot = full.find('.', start);
  std::string part = full.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
  // "objects[2]": the second table of the array [[...objects]] only.
  std::optional<std::size_t> element;
  if (const auto open = part.find('['); open != std::string::npos) {
    std::size_t n = 0, used = 0;
    try {
      n = std::stoul(part.substr(open + 1), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || n == 0 || part.substr(open + 1 + used) != "]" || dot == std::string::npos)
      throw InputError("", std::nullopt, origin, full, "expected an element of an array of tables as NAME[N].KEY, N counted from 1");
    element = n;
    part.erase(open);
  }
  if (part.empty()) throw InputError("", std::nullopt, origin, full, "expected a dotted key such as blade.speed");
  if (dot == std::string::npos) {
    put(table, part, value, origin);
    return;
  }
  if (element) {
    auto* array = table.get_as<toml::array>(part);
    if (!array || !array->is_array_of_tables() || *element > array->size())
      throw InputError("", std::nullopt, origin, full,
                       fmt::format("expected one of the {} [[{}]] tables the file has", array && array->is_array_of_tables() ? array->size() : 0,
                                   full.substr(0, full.find('[', start))));
    return set_in(*array->get(*element - 1)->as_table(), dot + 1, full, value, origin);
  }
  auto [it, inserted] = table.insert(part, toml::table{});
  if (auto* sub = it->second.as_table()) return set_in(*sub, dot + 1, full, value, origin);
  if (auto* array = it->second.as_array(); array && array->is_array_of_tables()) {
    for (auto& element_table : *array) set_in(*element_table.as_table(), dot + 1, full, value, origin);
    return;
  }
  throw InputError("", std::nullopt, origin, full + " = " + value, "cannot set a key inside '" + part + "', which is not a table");
}

}  // namespace

void set_key(toml::table& document, const std::string& key, const std::string& value, const std::string& origin) {
  set_in(document, 0, key, value, origin);
}

void assign(toml::table& document, const std::string& assignment, const std::string& origin) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("", std::nullopt, origin, assignment, "expected KEY=VALUE, for example blade.speed=\"1000 rpm\"");
  set_key(document, assignment.substr(0, eq), assignment.substr(eq + 1), origin);
}

}  // namespace j232::scenario
