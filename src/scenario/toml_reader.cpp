#include "scenario/toml_reader.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace j232::scenario {

TableReader::TableReader(const toml::table& table, std::string file, std::string path)
    : table_(&table), file_(std::move(file)), path_(std::move(path)), used_(std::make_shared<std::set<std::string, std::less<>>>()) {}

std::string TableReader::full(std::string_view key) const { return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key); }

const toml::node* TableReader::node(std::string_view key) const {
  used_->insert(std::string(key));
  return table_->get(key);
}

bool TableReader::has(std::string_view key) const { return table_->contains(key); }

bool TableReader::is_string(std::string_view key) const {
  const toml::node* n = table_->get(key);
  return n && n->is_string();
}

std::vector<std::string> TableReader::keys() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : *table_) out.emplace_back(k.str());
  return out;
}

namespace {
// Where a value came from when not from the file being read: set_key stores the value's
// origin as its source path ("--set" for a command-line option, the study input that drew
// it for a sweep or uq draw); a node with no source at all came from an option too.
struct Origin {
  bool from_file = true, command_line = false;
  std::string name;  // the origin's name, when neither the file nor the command line
};
Origin origin_of(const toml::node& n, const std::string& file) {
  const auto& path = n.source().path;
  if (!path || *path == "--set") return {false, true, {}};
  if (*path == file) return {};
  return {false, false, *path};
}
}  // namespace

std::optional<int> TableReader::line_of(std::string_view key) const {
  if (const toml::node* n = table_->get(key)) {
    if (!origin_of(*n, file_).from_file) return std::nullopt;
    return static_cast<int>(n->source().begin.line);
  }
  if (table_->source().begin.line > 0) return static_cast<int>(table_->source().begin.line);
  return std::nullopt;
}

InputError TableReader::error(std::string_view key, std::string expected) const {
  const toml::node* n = table_->get(key);
  // A value set by a command-line option blames the command line; one a study set (a sweep's
  // point, a uq draw), the study input that set it; else the file and line.
  const Origin origin = n ? origin_of(*n, file_) : Origin{};
  if (origin.command_line) return InputError("", std::nullopt, fmt::format("option for {}", full(key)), shown(*n), std::move(expected));
  if (!origin.from_file) return InputError(origin.name, std::nullopt, full(key), shown(*n), std::move(expected));
  return InputError(file_, line_of(key), full(key), n ? shown(*n) : std::string(), std::move(expected));
}

// The value as the user wrote it: strings in double quotes, numbers in shortest form.
std::string TableReader::shown(const toml::node& n) const {
  if (n.is_table()) return "{...}";
  if (n.is_array()) return "[...]";
  if (auto s = n.value_exact<std::string>()) return fmt::format("\"{}\"", *s);
  if (auto i = n.value_exact<int64_t>()) return fmt::format("{}", *i);
  if (auto d = n.value_exact<double>()) return fmt::format("{}", *d);
  if (auto b = n.value_exact<bool>()) return *b ? "true" : "false";
  std::ostringstream out;
  n.visit([&](const auto& v) { out << v; });
  return out.str();
}

namespace {
// An SI bound in words, in the unit a user of that kind of quantity reads most easily.
std::string bound(units::Kind kind, double v) {
  using units::Kind;
  switch (kind) {
    case Kind::Angle: return fmt::format("{:g} deg", v / units::degree);
    case Kind::AngularSpeed: return fmt::format("{:g} rpm", v / units::rpm);
    case Kind::Length: return fmt::format("{:g} m", v);
    case Kind::Mass: return fmt::format("{:g} kg", v);
    case Kind::Time: return fmt::format("{:g} s", v);
    case Kind::Speed: return fmt::format("{:g} m/s", v);
    case Kind::Inertia: return fmt::format("{:g} kg m^2", v);
    case Kind::Energy: return fmt::format("{:g} J", v);
    case Kind::EnergyPerLength: return fmt::format("{:g} J/m", v);
    case Kind::Acceleration: return fmt::format("{:g} m/s^2", v);
    case Kind::Density: return fmt::format("{:g} kg/m^3", v);
    case Kind::Area: return fmt::format("{:g} m^2", v);
    case Kind::PerArea: return fmt::format("{:g} m^-2", v);
    case Kind::Dimensionless: return fmt::format("{:g}", v);
  }
  return fmt::format("{:g}", v);
}
}  // namespace

std::string expected_words(units::Kind kind, const Range& r) {
  std::string what = fmt::format("expected {}", units::describe(kind));
  const bool low = std::isfinite(r.low), high = std::isfinite(r.high);
  if (low && high && r.low_open) return what + fmt::format(", above {} and at most {}", bound(kind, r.low), bound(kind, r.high));
  if (low && high) return what + fmt::format(", from {} to {}", bound(kind, r.low), bound(kind, r.high));
  if (low && r.low == 0.0) return what + (r.low_open ? ", greater than zero" : ", zero or more");
  if (low) return what + fmt::format(", {} {}", r.low_open ? "above" : "at least", bound(kind, r.low));
  if (high) return what + fmt::format(", at most {}", bound(kind, r.high));
  return what;
}

std::optional<double> TableReader::optional_quantity(std::string_view key, units::Kind kind, Range range) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  const std::string expected = expected_words(kind, range);
  double value = 0.0;
  if (auto s = n->value<std::string>()) {
    try {
      value = units::parse(*s, kind);
    } catch (const units::UnitError& e) {
      throw error(key, e.what());
    }
  } else if (auto d = n->value<double>(); d && (n->is_floating_point() || n->is_integer())) {
    if (kind != units::Kind::Dimensionless) throw error(key, fmt::format("a number needs a unit here; {}", expected));
    value = *d;
  } else {
    throw error(key, expected);
  }
  if (!std::isfinite(value) || !range.contains(value)) throw error(key, expected);
  return value;
}

std::vector<std::array<double, 2>> TableReader::points(std::string_view key, units::Kind kind, Range range, std::size_t min_points,
                                                       std::size_t max_points) const {
  const toml::node* n = node(key);
  const std::string expected = fmt::format(
      "expected {} to {} points [x, y] such as [[\"30 in\", \"-12 in\"], [\"30 in\", "
      "\"12 in\"]], each coordinate {}",
      min_points, max_points, expected_words(kind, range).substr(std::string("expected ").size()));
  if (!n) throw error(key, "missing; " + expected);
  const toml::array* list = n->as_array();
  if (!list || list->size() < min_points || list->size() > max_points) throw error(key, expected);
  std::vector<std::array<double, 2>> out;
  for (const auto& item : *list) {
    const toml::array* pair = item.as_array();
    if (!pair || pair->size() != 2) throw error(key, expected);
    std::array<double, 2> p{};
    for (std::size_t i = 0; i < 2; ++i) {
      const auto text = (*pair)[i].value_exact<std::string>();
      if (!text) throw error(key, expected);
      try {
        p[i] = units::parse(*text, kind);
      } catch (const units::UnitError& e) {
        throw error(key, fmt::format("{}: {}", *text, e.what()));
      }
      if (!std::isfinite(p[i]) || !range.contains(p[i])) throw error(key, expected);
    }
    out.push_back(p);
  }
  return out;
}

double TableReader::quantity(std::string_view key, units::Kind kind, Range range) const {
  if (auto v = optional_quantity(key, kind, range)) return *v;
  throw error(key, "missing; " + expected_words(kind, range));
}

double TableReader::quantity_or(std::string_view key, units::Kind kind, double fallback, Range range) const {
  return optional_quantity(key, kind, range).value_or(fallback);
}

std::string TableReader::string_or(std::string_view key, std::string fallback, const std::vector<std::string>& allowed) const {
  const toml::node* n = node(key);
  if (!n) return fallback;
  std::string choices;
  for (const auto& a : allowed) choices += (choices.empty() ? "\"" : ", \"") + a + "\"";
  auto s = n->value<std::string>();
  if (!s) throw error(key, allowed.empty() ? std::string("expected a string") : fmt::format("expected one of {}", choices));
  if (allowed.empty()) return *s;
  for (const auto& a : allowed)
    if (*s == a) return *s;
  throw error(key, fmt::format("expected one of {}", choices));
}

std::vector<std::string> TableReader::strings(std::string_view key, std::size_t max) const {
  const toml::node* n = node(key);
  std::vector<std::string> out;
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a || a->size() > max) throw error(key, fmt::format("expected an array of at most {} strings", max));
  for (const auto& item : *a) {
    auto s = item.value_exact<std::string>();
    if (!s) throw error(key, "expected an array of strings");
    out.push_back(*s);
  }
  return out;
}

std::optional<std::string> TableReader::value_at(std::string_view dotted) const {
  const toml::node* n = table_;
  std::size_t from = 0;
  while (n) {
    const std::size_t dot = dotted.find('.', from);
    const std::string_view part = dotted.substr(from, dot == std::string_view::npos ? std::string_view::npos : dot - from);
    const toml::table* t = n->as_table();
    if (!t || part.empty()) return std::nullopt;
    n = t->get(part);
    if (dot == std::string_view::npos) break;
    from = dot + 1;
  }
  if (!n || n->is_table() || n->is_array_of_tables()) return std::nullopt;
  return shown(*n);
}

double TableReader::percentage_or(std::string_view key, double fallback) const {
  const toml::node* n = node(key);
  if (!n) return fallback;
  const std::string expected = "expected a percentage with its unit, from \"0 %\" to \"100 %\", such as \"0.5 %\"";
  const auto text = n->value_exact<std::string>();
  if (!text || text->find('%') == std::string::npos) throw error(key, expected);
  try {
    const double v = units::parse(*text, units::Kind::Dimensionless);
    if (v >= 0.0 && v <= 1.0) return v;
  } catch (const units::UnitError&) {
  }
  throw error(key, expected);
}

bool TableReader::boolean_or(std::string_view key, bool fallback) const {
  const toml::node* n = node(key);
  if (!n) return fallback;
  if (!n->is_boolean()) throw error(key, "expected true or false");
  return *n->value<bool>();
}

long long TableReader::integer_or(std::string_view key, long long fallback, long long min, long long max) const {
  const toml::node* n = node(key);
  if (!n) return fallback;
  if (!n->is_integer()) throw error(key, fmt::format("expected a whole number from {} to {}", min, max));
  const long long v = *n->value<long long>();
  if (v < min || v > max) throw error(key, fmt::format("expected a whole number from {} to {}", min, max));
  return v;
}

std::optional<std::uint64_t> parse_unsigned64(std::string_view text) {
  std::uint64_t v = 0;
  const char* last = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), last, v);
  if (text.empty() || ec != std::errc() || ptr != last) return std::nullopt;
  return v;
}

std::uint64_t TableReader::unsigned64_or(std::string_view key, std::uint64_t fallback) const {
  const toml::node* n = node(key);
  if (!n) return fallback;
  const std::string expected = "expected a whole number from 0 to 18446744073709551615 (larger than 2^63: as a string)";
  if (n->is_integer()) {
    const long long v = *n->value<long long>();
    if (v < 0) throw error(key, expected);
    return static_cast<std::uint64_t>(v);
  }
  if (auto s = n->value_exact<std::string>())
    if (auto v = parse_unsigned64(*s)) return *v;
  throw error(key, expected);
}

std::optional<TableReader> TableReader::table(std::string_view key) const {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  if (!n->is_table()) throw error(key, "expected a table");
  return TableReader(*n->as_table(), file_, full(key));
}

std::vector<TableReader> TableReader::array_of_tables(std::string_view key, std::size_t max) const {
  const toml::node* n = node(key);
  std::vector<TableReader> out;
  if (!n) return out;
  const toml::array* array = n->as_array();
  if (!array) throw error(key, "expected an array of tables ([[" + full(key) + "]])");
  if (array->size() > max) throw error(key, fmt::format("{} tables; expected at most {} [[{}]] tables", array->size(), max, full(key)));
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::table* t = (*array)[i].as_table();
    if (!t) throw error(key, "expected an array of tables ([[" + full(key) + "]])");
    out.emplace_back(*t, file_, fmt::format("{}[{}]", full(key), i + 1));
  }
  return out;
}

void TableReader::refuse_unknown_keys() const {
  for (const auto& [k, v] : *table_) {
    if (used_->count(k.str())) continue;
    std::string known;
    for (const auto& u : *used_) known += (known.empty() ? "" : ", ") + u;
    // A key set from the command line (--set) or by a study has no place in the file: blame
    // the option or the study.
    const Origin origin = origin_of(v, file_);
    std::string expected =
        known.empty() ? std::string("unknown key (this table takes no keys)") : fmt::format("unknown key; this table takes: {}", known);
    if (origin.command_line) throw InputError("", std::nullopt, fmt::format("option for {}", full(k.str())), "", std::move(expected));
    throw InputError(origin.from_file ? file_ : origin.name,
                     origin.from_file ? std::optional<int>(static_cast<int>(v.source().begin.line)) : std::nullopt, full(k.str()), "",
                     std::move(expected));
  }
}

toml::table parse_toml_file(const std::string& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status)) throw InputError::file_problem(file, std::nullopt, "no such file");
  if (std::filesystem::is_directory(status))
    throw InputError::file_problem(file, std::nullopt, "is a folder; expected a scenario file (TOML)");
  if (!std::filesystem::is_regular_file(status))
    throw InputError::file_problem(file, std::nullopt, "not a regular file; expected a scenario file (TOML)");
  if (std::filesystem::file_size(file, ec) > (4u << 20))
    throw InputError::file_problem(file, std::nullopt, "larger than 4 MB; a scenario file is a page of settings");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError::file_problem(file, std::nullopt, "cannot open the file for reading");
  std::stringstream buffer;
  buffer << in.rdbuf();
  try {
    return toml::parse(buffer.str(), file);
  } catch (const toml::parse_error& e) {
    throw InputError::file_problem(file, static_cast<int>(e.source().begin.line), fmt::format("not valid TOML: {}", e.description()));
  }
}

}  // namespace j232::scenario
