#pragma once
// Typed, checked access to one TOML table. Every read names the key's full path
// (blade.hub.bar_mass) and line in its error; keys the program does not know are
// refused (a typo must not silently fall back to a default).
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <toml++/toml.h>
#include <vector>

#include "scenario/input_error.hpp"
#include "units/quantity.hpp"

namespace j232::scenario {

enum class Range { Any, Positive, NonNegative, UnitInterval };

class TableReader {
 public:
  TableReader(const toml::table& table, std::string file, std::string path);

  bool has(std::string_view key) const;

  // A quantity written with units ("22 lb"); plain numbers only for Kind::Dimensionless.
  double quantity(std::string_view key, units::Kind kind, Range range = Range::Any) const;
  double quantity_or(std::string_view key, units::Kind kind, double fallback, Range range = Range::Any) const;
  std::optional<double> optional_quantity(std::string_view key, units::Kind kind, Range range = Range::Any) const;

  std::string string_or(std::string_view key, std::string fallback, const std::vector<std::string>& allowed) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  long long integer_or(std::string_view key, long long fallback, long long min, long long max) const;

  std::optional<TableReader> table(std::string_view key) const;
  std::vector<TableReader> array_of_tables(std::string_view key) const;

  // Throws for the first key in the table that was never asked for.
  void refuse_unknown_keys() const;

  // An error about `key` of this table (for checks that span several keys).
  InputError error(std::string_view key, std::string expected) const;
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  std::optional<int> line_of(std::string_view key) const;

 private:
  const toml::node* node(std::string_view key) const;
  std::string full(std::string_view key) const;
  std::string shown(const toml::node& node) const;

  const toml::table* table_;
  std::string file_;
  std::string path_;
  std::shared_ptr<std::set<std::string, std::less<>>> used_;
};

// Parses a whole file; malformed TOML becomes an InputError with line and reason.
toml::table parse_toml_file(const std::string& file);

}  // namespace j232::scenario
