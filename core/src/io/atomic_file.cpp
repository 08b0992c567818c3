#include "plmap/core/io/atomic_file.hpp"

#include "plmap/core/errors.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

namespace plmap {
namespace {

// ---- names -------------------------------------------------------------------------------------

/// Long target names are cut in the temporary's name, which must stay under the 255 bytes a
/// file name may have; the cut name is still recognisable.
constexpr std::size_t max_name_in_temporary = 100;

std::string host_name() {
  std::array<char, 256> buffer{};
  if (::gethostname(buffer.data(), buffer.size() - 1) != 0 || buffer[0] == '\0') return "host";
  return buffer.data();
}

/// `.NAME.plmap-tmp-HOST-`: what every temporary of `target` written on this host starts with.
/// The host is part of it because a process id means something only on its own host (a
/// directory may be shared over the network).
std::string temporary_prefix(const std::filesystem::path& target) {
  std::string name = target.filename().string();
  if (name.size() > max_name_in_temporary) name.resize(max_name_in_temporary);
  static const std::string host = host_name();
  return "." + name + ".plmap-tmp-" + host + "-";
}

/// `.NAME.plmap-tmp-HOST-PID-N[SUFFIX]`: no other writer (thread or process) picks the same name.
std::filesystem::path temporary_sibling(const std::filesystem::path& path, const std::string& suffix) {
  static std::atomic<unsigned long> counter{0};
  return path.parent_path() / (temporary_prefix(path) + std::to_string(::getpid()) + "-" +
                               std::to_string(counter.fetch_add(1)) + suffix);
}

std::string system_message(int error_number) {
  return std::error_code(error_number, std::generic_category()).message();
}

std::filesystem::path directory_of(const std::filesystem::path& path) {
  return path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
}

// ---- removal on signals ------------------------------------------------------------------------

/// The temporaries being written, for the signal handler, which may only read plain memory and
/// call async-signal-safe functions (unlink). A slot is free (0), being filled (1) or holds a path
/// (2). With more temporaries at once than slots, the extra ones are only removed by
/// remove_stale_temporaries on a later run.
constexpr int slot_free = 0, slot_filling = 1, slot_ready = 2;
struct SignalSlot {
  std::atomic<int> state{slot_free};
  char path[4096];
};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the slot states");
SignalSlot signal_slots[64];

int register_for_signals(const std::filesystem::path& path) {
  const std::string& text = path.native();
  if (text.size() >= sizeof(SignalSlot::path)) return -1;
  for (int i = 0; i < static_cast<int>(std::size(signal_slots)); ++i) {
    int expected = slot_free;
    if (signal_slots[i].state.compare_exchange_strong(expected, slot_filling)) {
      std::memcpy(signal_slots[i].path, text.c_str(), text.size() + 1);
      signal_slots[i].state.store(slot_ready);
      return i;
    }
  }
  return -1;
}

extern "C" void remove_temporaries_and_reraise(int signal_number) {
  for (auto& slot : signal_slots)
    if (slot.state.load() == slot_ready) ::unlink(slot.path);
  // End the process as the signal would have, so that the parent sees "killed by SIGINT".
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
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

/// Why the file cannot be created, in the user's terms (the temporary's name means nothing to them).
std::string creation_failure(const std::filesystem::path& path, int error_number) {
  std::error_code ec;
  const std::filesystem::path directory = directory_of(path);
  if (!std::filesystem::exists(directory, ec))
    return path.string() + ": cannot write: directory " + directory.string() + " does not exist";
  if (!std::filesystem::is_directory(directory, ec))
    return path.string() + ": cannot write: " + directory.string() + " is not a directory";
  if (error_number == ENOENT)  // the directory exists but takes no new files (/proc, ...)
    return path.string() + ": cannot write: cannot create files in " + directory.string();
  return path.string() + ": cannot write: " + system_message(error_number);
}

}  // namespace

// ---- TemporaryFile -----------------------------------------------------------------------------

TemporaryFile::TemporaryFile(const std::filesystem::path& target, const std::string& suffix)
    : path_(temporary_sibling(target, suffix)), signal_slot_(register_for_signals(path_)) {}

TemporaryFile::~TemporaryFile() {
  if (!released_) {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  if (signal_slot_ >= 0) signal_slots[signal_slot_].state.store(slot_free);
}

void TemporaryFile::release() {
  released_ = true;
  if (signal_slot_ >= 0) signal_slots[signal_slot_].state.store(slot_free);
  signal_slot_ = -1;
}

void remove_stale_temporaries(const std::filesystem::path& target) {
  const std::string prefix = temporary_prefix(target);
  std::error_code ec;
  std::filesystem::directory_iterator entries(directory_of(target), ec);
  if (ec) return;
  for (auto it = entries; it != std::filesystem::directory_iterator(); it.increment(ec)) {
    if (ec) return;
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const char* const first = name.data() + prefix.size();
    const char* const last = name.data() + name.size();
    pid_t pid = 0;
    const auto [end, parse_error] = std::from_chars(first, last, pid);
    if (parse_error != std::errc() || end == last || *end != '-' || pid <= 0) continue;
    if (pid == ::getpid()) continue;  // another thread of this process may be writing it
    if (::kill(pid, 0) == 0 || errno != ESRCH) continue;  // running (EPERM: someone else's)
    std::error_code ignored;
    std::filesystem::remove(it->path(), ignored);
  }
}

void remove_temporaries_on_signals() {
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
    struct sigaction previous {};
    if (::sigaction(signal_number, nullptr, &previous) != 0) continue;
    if (previous.sa_handler != SIG_DFL) continue;  // ignored (nohup) or someone else's handler
    struct sigaction action {};
    action.sa_handler = remove_temporaries_and_reraise;
    sigemptyset(&action.sa_mask);
    ::sigaction(signal_number, &action, nullptr);
  }
}

// ---- write_file_atomically ---------------------------------------------------------------------

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& writer, bool binary) {
  const std::string shown = path.string();
  if (path.filename().empty()) throw Error(shown + ": not a file name");
  remove_stale_temporaries(path);
  TemporaryFile temporary(path);
  {
    std::ofstream out;
    errno = 0;
    out.open(temporary.path(), binary ? std::ios::out | std::ios::trunc | std::ios::binary
                                      : std::ios::out | std::ios::trunc);
    if (!out) throw Error(creation_failure(path, errno));
    writer(out);
    out.flush();
    if (!out) throw Error(shown + ": write failed: " + system_message(errno));
    out.close();
    if (out.fail()) throw Error(shown + ": write failed when closing the file");
  }
  if (const int e = sync_path(temporary.path(), O_RDONLY); e != 0) {
    throw Error(shown + ": fsync failed: " + system_message(e));
  }
  std::error_code rename_error;
  std::filesystem::rename(temporary.path(), path, rename_error);
  if (rename_error) throw Error(shown + ": cannot replace the file: " + rename_error.message());
  temporary.release();
  // Make the rename itself durable. A failure here leaves a complete file in place, so it is
  // not worth an error: the data is written, only its survival across a power cut is unsure.
  (void)sync_path(directory_of(path), O_RDONLY | O_DIRECTORY);
}

}  // namespace plmap
