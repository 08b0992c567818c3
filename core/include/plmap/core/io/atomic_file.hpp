#pragma once
/// \file
/// Writing a file so that readers never see it half-written: the content goes to a temporary
/// file in the target's directory, is flushed to disk, and only then renamed over the target.
/// If anything fails (the writer throws, the disk is full), the previous file stays untouched.
///
/// Temporary files are named `.NAME.plmap-tmp-HOST-PID-N[SUFFIX]` beside the target NAME, so
/// that one left behind by a killed process is recognisable as plmap's, and so that the next
/// write of the same target on the same host can tell that its process is gone and remove it.

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>

namespace plmap {

/// Writes `path` atomically. `writer` streams the whole content into the given stream; `binary`
/// opens the temporary file in binary mode. Throws plmap::Error naming `path` (never the
/// temporary file) if the file cannot be created, written, synced or renamed; rethrows whatever
/// `writer` throws. In both cases the temporary file is removed and `path` is unchanged.
/// Before writing, removes the temporaries of `path` that dead processes left behind.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& writer, bool binary);

/// A fresh temporary file name beside `target` (the file is not created), with the recognisable
/// name described above; it is removed when this object is destroyed, unless released, and also
/// if the program is stopped by a signal after remove_temporaries_on_signals(). For callers that
/// let another program write the file (e.g. a converter) and then rename it into place.
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::filesystem::path& target, const std::string& suffix = "");
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile();

  const std::filesystem::path& path() const { return path_; }

  /// The file has been renamed away: do not remove it any more.
  void release();

 private:
  std::filesystem::path path_;
  int signal_slot_ = -1;  // index in the registry the signal handler reads, or -1
  bool released_ = false;
};

/// Removes the temporary files of `target` (named as above) whose process no longer runs on
/// this host. Never throws; files it cannot remove stay.
void remove_stale_temporaries(const std::filesystem::path& target);

/// For programs: installs handlers of SIGINT, SIGTERM, SIGHUP and SIGQUIT that remove the
/// temporary files being written and then let the signal end the process as it would have.
/// Signals the program ignores stay ignored. Call once, early in main().
void remove_temporaries_on_signals();

}  // namespace plmap
