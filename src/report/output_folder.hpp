#pragma once
// An output folder that is written as a set. A run first takes the folder's lock (a
// second run into the same folder is refused with a message, not mixed in), checks that
// the folder can be written (before any simulation), and writes its files into a staging
// folder inside it. commit() then moves them into place with result.json removed first
// and put back last: a folder whose result.json is present holds one complete set, and
// result.json's provenance names the size and digest of each of its siblings. A run
// killed part-way leaves no result.json and a staging folder, which the next run into
// the folder removes. A complete earlier result is never lost: it is moved, as a set,
// into previous-N inside the folder.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "report/atomic_file.hpp"  // report::FileError

namespace j232::report {

// FNV-1a, 64 bit: a change detector (inputs, output files), not a security hash.
struct Fnv {
  std::uint64_t h = 1469598103934665603ULL;
  void add(std::string_view bytes) {
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ULL;
  }
  std::string hex() const;
};

// Now, in UTC, as results' provenance gives it ("2026-11-24T22:00:14Z").
std::string utc_now();

class OutputFolder {
 public:
  // `files`: the names the run will write; the last is the one whose presence marks the set complete.
  OutputFolder(std::string folder, std::vector<std::string> files);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::string& folder() const { return folder_; }
  // Where to write `name` before commit().
  std::string staged(const std::string& name) const;
  // Moves the new set into place. A complete earlier result there is kept in the folder's
  // first free previous-N (said on standard error), never replaced.
  void commit();
  // Where commit() kept an earlier result (empty: there was none).
  const std::string& kept_previous() const { return kept_previous_; }

 private:
  std::string folder_, staging_, kept_previous_;
  std::vector<std::string> files_;
  int lock_fd_ = -1;
  bool private_ = false;  // a rank other than 0 of an MPI job: a private folder, discarded
};

// A file written a piece at a time (marks.csv as the run goes), with its size and digest.
class StreamedFile {
 public:
  explicit StreamedFile(const std::string& path);
  ~StreamedFile();
  StreamedFile(const StreamedFile&) = delete;
  StreamedFile& operator=(const StreamedFile&) = delete;
  void write(std::string_view text);
  void close();  // flushes; throws report::FileError on failure
  std::uint64_t bytes() const { return bytes_; }
  std::string digest() const { return fnv_.hex(); }

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  std::uint64_t bytes_ = 0;
  Fnv fnv_;
};

}  // namespace j232::report
