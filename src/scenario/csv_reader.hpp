#pragma once
// A small CSV reader for tables users write by hand (calibration cases, drop tests):
// comma-separated, fields optionally in double quotes ("" for a quote inside), blank lines
// and lines starting with '#' skipped, the first other line the header. Every row must have
// the header's number of fields. Errors name the file and line.
#include <string>

#include "units/quantity.hpp"
#include <vector>

namespace j232::scenario {

struct CsvRow {
  int line = 0;  // 1-based, in the file
  std::vector<std::string> fields;
};

struct CsvTable {
  std::string file;
  int header_line = 0;
  std::vector<std::string> header;
  std::vector<CsvRow> rows;
  // The column named `name`, or -1.
  int column(const std::string& name) const;
};

// Throws InputError (cannot open, a quote left open, a row of the wrong width, no rows).
CsvTable read_csv(const std::string& file);
// The same from text; `file` names it in errors.
CsvTable parse_csv(const std::string& text, const std::string& file);
// The column `name`, or InputError naming the file, the header line and `what` it should hold.
int require_column(const CsvTable& t, const std::string& name, const std::string& what);
// A cell read as a quantity of `kind` ("12 m/s"), or InputError naming the file, line,
// column, the text and what was expected.
double quantity_cell(const CsvTable& t, const CsvRow& row, int column, units::Kind kind);

}  // namespace j232::scenario
