#include "scenario/csv_reader.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "scenario/input_error.hpp"

namespace j232::scenario {

int CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return static_cast<int>(i);
  return -1;
}

namespace {
std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

// One line's fields; a quoted field keeps its spaces, an unquoted one is trimmed.
std::vector<std::string> split(const std::string& line, const std::string& file, int number) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false, was_quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
        field += '"', ++i;
      else if (c == '"')
        quoted = false;
      else
        field += c;
    } else if (c == '"' && trim(field).empty()) {
      quoted = was_quoted = true;
      field.clear();
    } else if (c == ',') {
      fields.push_back(was_quoted ? field : trim(field));
      field.clear();
      was_quoted = false;
    } else {
      field += c;
    }
  }
  if (quoted) throw InputError::file_problem(file, number, "a quoted field is not closed on this line");
  fields.push_back(was_quoted ? field : trim(field));
  return fields;
}
}  // namespace

CsvTable parse_csv(const std::string& text, const std::string& file) {
  CsvTable t;
  t.file = file;
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string bare = trim(line);
    if (bare.empty() || bare[0] == '#') continue;
    auto fields = split(line, file, number);
    if (t.header.empty()) {
      t.header = std::move(fields);
      t.header_line = number;
      continue;
    }
    if (fields.size() != t.header.size())
      throw InputError::file_problem(file, number,
                                     fmt::format("{} fields; expected {}, one per column of the header ({})", fields.size(),
                                                 t.header.size(), fmt::join(t.header, ", ")));
    t.rows.push_back({number, std::move(fields)});
  }
  if (t.header.empty() || t.rows.empty()) throw InputError::file_problem(file, std::nullopt, "expected a header line and at least one row");
  return t;
}

CsvTable read_csv(const std::string& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw InputError::file_problem(file, std::nullopt, "no such file");
  std::ifstream in(file);
  if (!in) throw InputError::file_problem(file, std::nullopt, "cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return parse_csv(text.str(), file);
}

int require_column(const CsvTable& t, const std::string& name, const std::string& what) {
  const int c = t.column(name);
  if (c < 0) throw InputError::file_problem(t.file, t.header_line, fmt::format("no column \"{}\"; expected {}", name, what));
  return c;
}

double quantity_cell(const CsvTable& t, const CsvRow& row, int column, units::Kind kind) {
  const std::string& text = row.fields[static_cast<std::size_t>(column)];
  try {
    return units::parse(text, kind);
  } catch (const units::UnitError& e) {
    throw InputError(t.file, row.line, t.header[static_cast<std::size_t>(column)], text,
                     fmt::format("expected {} ({})", units::describe(kind), e.what()));
  }
}

}  // namespace j232::scenario
