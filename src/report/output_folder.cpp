#include "report/output_folder.hpp"

#include "assess/cluster.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

namespace j232::report {

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}


namespace fs = std::filesystem;

namespace {
constexpr const char* kLockName = ".j232.lock";
constexpr const char* kStagingPrefix = ".j232-staging-";

[[noreturn]] void refuse(const std::string& path, const std::string& why) { throw report::FileError(fmt::format("{}: {}", path, why)); }
}  // namespace

std::string Fnv::hex() const { return fmt::format("{:016x}", h); }

OutputFolder::OutputFolder(std::string folder, std::vector<std::string> files) : folder_(std::move(folder)), files_(std::move(files)) {
  std::error_code ec;
  if (!assess::cluster::is_writer()) {
    // Another rank of an MPI job: it computes what rank 0 writes, and writes nothing of its
    // own into the folder; what it stages goes to a private folder, removed at the end.
    std::string temp = (fs::temp_directory_path(ec) / "j232-rank-XXXXXX").string();
    if (!::mkdtemp(temp.data())) refuse(temp, fmt::format("cannot create a private folder: {}", std::strerror(errno)));
    folder_ = staging_ = temp;
    private_ = true;
    return;
  }
  if (fs::exists(folder_, ec) && !fs::is_directory(folder_, ec))
    refuse(folder_, "exists and is not a folder; expected an output folder (--out)");
  fs::create_directories(folder_, ec);
  if (ec) refuse(folder_, "cannot create the output folder: " + ec.message());

  const std::string lock = (fs::path(folder_) / kLockName).string();
  lock_fd_ = ::open(lock.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) refuse(folder_, fmt::format("cannot write into the output folder: {}", std::strerror(errno)));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(lock_fd_);
    lock_fd_ = -1;
    refuse(folder_, err == EWOULDBLOCK ? "another j232 run is writing into this folder; wait for it to finish or choose "
                                         "another --out"
                                       : fmt::format("cannot lock the output folder: {}", std::strerror(err)));
  }
  // Leftovers of runs that were killed (we hold the lock: nobody else is using them).
  for (const auto& entry : fs::directory_iterator(folder_, ec))
    if (entry.path().filename().string().rfind(kStagingPrefix, 0) == 0) fs::remove_all(entry.path(), ec);
  for (const auto& f : files_) {
    const fs::path target = fs::path(folder_) / f;
    if (fs::exists(fs::symlink_status(target, ec)) && !fs::is_regular_file(fs::symlink_status(target, ec)))
      refuse(target.string(), "exists and is not a regular file; remove it or choose another --out");
  }
  staging_ = (fs::path(folder_) / fmt::format("{}{}", kStagingPrefix, ::getpid())).string();
  fs::create_directory(staging_, ec);
  if (ec) refuse(staging_, "cannot create a folder for the new results: " + ec.message());
}

OutputFolder::~OutputFolder() {
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

std::string OutputFolder::staged(const std::string& name) const { return (fs::path(staging_) / name).string(); }

void OutputFolder::commit() {
  std::error_code ec;
  if (private_) return;  // removed with the object
  const fs::path complete = fs::path(folder_) / files_.back();
  // A complete earlier result in the folder is kept, not replaced: its files move together
  // into the first free previous-N beside the new set (their digests in its result stay true).
  if (fs::exists(complete, ec)) {
    fs::path kept;
    for (int n = 1;; ++n) {
      kept = fs::path(folder_) / fmt::format("previous-{}", n);
      if (!fs::exists(kept, ec)) break;
    }
    fs::create_directory(kept, ec);
    if (ec) refuse(kept.string(), "cannot keep the earlier result there: " + ec.message());
    for (const auto& f : files_) {
      const fs::path old = fs::path(folder_) / f;
      if (!fs::exists(fs::symlink_status(old, ec))) continue;
      fs::rename(old, kept / f, ec);
      if (ec) refuse(old.string(), "cannot keep the earlier result: " + ec.message());
    }
    kept_previous_ = kept.string();
    std::fprintf(stderr, "j232: %s held an earlier result: kept in %s\n", folder_.c_str(), kept_previous_.c_str());
  }
  fs::remove(complete, ec);  // the set is incomplete from here until the last rename
  if (ec) refuse(complete.string(), "cannot replace: " + ec.message());
  for (const auto& f : files_) {
    fs::rename(staged(f), fs::path(folder_) / f, ec);
    if (ec) refuse((fs::path(folder_) / f).string(), "cannot move the new file into place: " + ec.message());
  }
}

StreamedFile::StreamedFile(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "wb")) {
  if (!file_) refuse(path, fmt::format("cannot write: {}", std::strerror(errno)));
}

StreamedFile::~StreamedFile() {
  if (file_) std::fclose(file_);
}

void StreamedFile::write(std::string_view text) {
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) refuse(path_, fmt::format("write failed: {}", std::strerror(errno)));
  bytes_ += text.size();
  fnv_.add(text);
}

void StreamedFile::close() {
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fflush(f) != 0 || std::fclose(f) != 0) refuse(path_, fmt::format("write failed: {}", std::strerror(errno)));
}

}  // namespace j232::report
