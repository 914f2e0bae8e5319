#pragma once
// Bad input is refused with a message a user can act on: where (file and line),
// which key, the value given, and what was expected.
#include <optional>
#include <stdexcept>
#include <string>

namespace j232::scenario {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::optional<int> line, std::string key, std::string value, std::string expected);
  // A whole-file problem (cannot open, malformed TOML).
  static InputError file_problem(std::string file, std::optional<int> line, std::string what);

  const std::string& file() const { return file_; }
  std::optional<int> line() const { return line_; }
  const std::string& key() const { return key_; }

 private:
  InputError(std::string message, std::string file, std::optional<int> line, std::string key);
  std::string file_;
  std::optional<int> line_;
  std::string key_;
};

}  // namespace j232::scenario
