#pragma once
// Writes a whole file or nothing: the text goes to PATH.partial, is flushed, and is
// renamed over PATH, so a crash or Ctrl-C never leaves a half-written result.
#include <string>
#include <string_view>

namespace j232::report {

// Throws std::runtime_error naming the path on failure.
void write_atomically(const std::string& path, std::string_view content);

}  // namespace j232::report
