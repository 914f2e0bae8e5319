#pragma once
// Writes a whole file or nothing: the text goes to PATH.partial, is flushed, and is
// renamed over PATH, so a crash or Ctrl-C never leaves a half-written result.
#include <stdexcept>
#include <string>
#include <string_view>

namespace j232::report {

// The file system refused something (not writable, disk full, a folder where a file
// should be, another run holding a lock): a fault of the environment, not a bug. The
// message starts with the path and ends with the system's reason.
class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws FileError on failure.
void write_atomically(const std::string& path, std::string_view content);

}  // namespace j232::report
