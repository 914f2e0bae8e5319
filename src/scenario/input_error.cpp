#include "scenario/input_error.hpp"

#include <fmt/format.h>

namespace j232::scenario {
namespace {
std::string where(const std::string& file, std::optional<int> line) {
  if (file.empty()) return "command line";
  return line ? fmt::format("{}:{}", file, *line) : file;
}

std::string message(const std::string& file, std::optional<int> line, const std::string& key, const std::string& value,
                    const std::string& expected) {
  return value.empty() ? fmt::format("{}: {}: {}", where(file, line), key, expected)
                       : fmt::format("{}: {} = {}: {}", where(file, line), key, value, expected);
}
}  // namespace

// The message is built before any argument is moved into a member.
InputError::InputError(std::string file, std::optional<int> line, std::string key, std::string value, std::string expected)
    : InputError(message(file, line, key, value, expected), file, line, key) {}

InputError::InputError(std::string message, std::string file, std::optional<int> line, std::string key)
    : std::runtime_error(std::move(message)), file_(std::move(file)), line_(line), key_(std::move(key)) {}

InputError InputError::file_problem(std::string file, std::optional<int> line, std::string what) {
  std::string message = fmt::format("{}: {}", where(file, line), what);
  return InputError(std::move(message), std::move(file), line, "");
}

}  // namespace j232::scenario
