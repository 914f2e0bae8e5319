#pragma once
// Typed, checked access to one TOML table. Every read names the key's full path
// (blade.hub.bar_mass) and line in its error; keys the program does not know are
// refused (a typo must not silently fall back to a default).
#include <array>
#include <cmath>
#include <cstdint>
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

// The values a key accepts, in SI. Besides the sign rules, a plausibility range keeps
// an input within what a mower, a nail or a test lab can physically be: a slip of unit
// ("22 m" for 22 in) is refused with the range instead of simulating a meaningless test.
struct Range {
  double low = -HUGE_VAL, high = HUGE_VAL;
  bool low_open = false;  // low itself is refused (positive quantities)

  static const Range Any, Positive, NonNegative, UnitInterval;
  // [low, high]; (0, high] with `positive`.
  static constexpr Range between(double low, double high) { return {low, high, false}; }
  static constexpr Range positive_up_to(double high) { return {0.0, high, true}; }
  bool contains(double v) const { return (low_open ? v > low : v >= low) && v <= high; }
};
inline constexpr Range Range::Any{};
inline constexpr Range Range::Positive{0.0, HUGE_VAL, true};
inline constexpr Range Range::NonNegative{0.0, HUGE_VAL, false};
inline constexpr Range Range::UnitInterval{0.0, 1.0, false};

// "expected a length such as \"24 in\", from 0.005 m to 0.3 m": what a key accepts, in words.
std::string expected_words(units::Kind kind, const Range& range);

class TableReader {
 public:
  TableReader(const toml::table& table, std::string file, std::string path);

  bool has(std::string_view key) const;
  // The key holds a string (a quantity, or a name); asks nothing, so marks nothing as used.
  bool is_string(std::string_view key) const;
  // Every key the table holds, in order.
  std::vector<std::string> keys() const;

  // A quantity written with units ("22 lb"); plain numbers only for Kind::Dimensionless.
  double quantity(std::string_view key, units::Kind kind, Range range = Range::Any) const;
  double quantity_or(std::string_view key, units::Kind kind, double fallback, Range range = Range::Any) const;
  std::optional<double> optional_quantity(std::string_view key, units::Kind kind, Range range = Range::Any) const;

  // A polyline in plan: [["30 in", "-12 in"], ["30 in", "12 in"], ...], each coordinate a
  // quantity of `kind` within `range`, min_points to max_points points.
  std::vector<std::array<double, 2>> points(std::string_view key, units::Kind kind, Range range, std::size_t min_points,
                                            std::size_t max_points) const;

  std::string string_or(std::string_view key, std::string fallback, const std::vector<std::string>& allowed) const;
  // An array of strings (none: empty).
  std::vector<std::string> strings(std::string_view key, std::size_t max = 256) const;
  // The value at a dotted path below this table ("housing.skirt_bottom"), as the user wrote
  // it; none when the path names no value (a table, an array of tables, nothing).
  std::optional<std::string> value_at(std::string_view dotted) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  // A percentage written with its unit ("0.5 %"), 0 to 100 %, as a fraction.
  double percentage_or(std::string_view key, double fallback) const;
  long long integer_or(std::string_view key, long long fallback, long long min, long long max) const;
  // A full unsigned 64-bit value (a seed): an integer, or a string for values beyond
  // TOML's signed 64-bit integers ("18446744073709551615").
  std::uint64_t unsigned64_or(std::string_view key, std::uint64_t fallback) const;

  std::optional<TableReader> table(std::string_view key) const;
  // At most `max` tables: an input that asks for thousands of links or meshes is a
  // mistake, and would only exhaust memory.
  std::vector<TableReader> array_of_tables(std::string_view key, std::size_t max = 64) const;

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

// A whole unsigned 64-bit number in decimal, or nothing (out of range, sign, junk).
std::optional<std::uint64_t> parse_unsigned64(std::string_view text);

// Parses a whole file; malformed TOML becomes an InputError with line and reason.
toml::table parse_toml_file(const std::string& file);

}  // namespace j232::scenario
