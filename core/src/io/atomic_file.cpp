#include "plmap/core/io/atomic_file.hpp"

#include "plmap/core/errors.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

namespace plmap {
namespace {

/// A name in the target's directory that no concurrent writer (thread or process) will pick:
/// the process id, a per-process counter and a time stamp.
std::filesystem::path temporary_sibling(const std::filesystem::path& path) {
  static std::atomic<unsigned long> counter{0};
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  std::string name = "." + path.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                     std::to_string(counter.fetch_add(1)) + "-" + std::to_string(stamp);
  return path.parent_path() / name;
}

std::string system_message(int error_number) {
  return std::error_code(error_number, std::generic_category()).message();
}

/// fsync a file or directory by path; the ofstream API has no way to reach the descriptor.
/// Returns errno on failure, 0 on success.
int sync_path(const std::filesystem::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return errno;
  int result = 0;
  if (::fsync(fd) != 0) result = errno;
  ::close(fd);
  return result;
}

/// Removes the temporary file unless it has been committed (renamed away).
class TemporaryFileGuard {
 public:
  explicit TemporaryFileGuard(std::filesystem::path path) : path_(std::move(path)) {}
  TemporaryFileGuard(const TemporaryFileGuard&) = delete;
  TemporaryFileGuard& operator=(const TemporaryFileGuard&) = delete;
  ~TemporaryFileGuard() {
    if (!committed_) {
      std::error_code ignored;
      std::filesystem::remove(path_, ignored);
    }
  }
  void commit() { committed_ = true; }

 private:
  std::filesystem::path path_;
  bool committed_ = false;
};

}  // namespace

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& writer, bool binary) {
  const std::string shown = path.string();
  if (path.filename().empty()) throw Error(shown + ": not a file name");
  const std::filesystem::path temporary = temporary_sibling(path);
  TemporaryFileGuard guard(temporary);
  {
    std::ofstream out;
    out.open(temporary, binary ? std::ios::out | std::ios::trunc | std::ios::binary
                               : std::ios::out | std::ios::trunc);
    if (!out) {
      throw Error(shown + ": cannot create temporary file " + temporary.string() + ": " +
                  system_message(errno));
    }
    writer(out);
    out.flush();
    if (!out) throw Error(shown + ": write failed: " + system_message(errno));
    out.close();
    if (out.fail()) throw Error(shown + ": closing the temporary file failed");
  }
  if (const int e = sync_path(temporary, O_RDONLY); e != 0) {
    throw Error(shown + ": fsync failed: " + system_message(e));
  }
  std::error_code rename_error;
  std::filesystem::rename(temporary, path, rename_error);
  if (rename_error) {
    throw Error(shown + ": cannot rename temporary file into place: " + rename_error.message());
  }
  guard.commit();
  // Make the rename itself durable. A failure here leaves a complete file in place, so it is
  // not worth an error: the data is written, only its survival across a power cut is unsure.
  const std::filesystem::path directory =
      path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  (void)sync_path(directory, O_RDONLY | O_DIRECTORY);
}

}  // namespace plmap
