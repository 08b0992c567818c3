#pragma once
/// \file
/// The one progress display of the `plmap` tool: turns the library's progress calls
/// (plmap::ProgressCallback) into a bar on stderr.
///
/// - On a terminal (stderr is a tty) a single line redrawn in place: phase, percentage and bar,
///   or a count when the phase's size is unknown; at most ten redraws a second; the line is
///   cleared when the command ends, so the command's own output starts on a clean line.
/// - On a pipe nothing, unless `--progress` asks for it: then plain lines without carriage
///   returns, one when a phase starts or ends and at most one a second in between.
/// - Only ever on stderr: `--json` output on stdout stays clean.

#include <plmap/core/io/map_file.hpp>
#include <plmap/core/progress.hpp>

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <string>

namespace plmap::cli {

/// What `--progress` / `--no-progress` chose.
enum class ProgressMode {
  automatic,  ///< a bar if stderr is a terminal, else nothing
  always,     ///< `--progress`: also on a pipe (plain lines there)
  never,      ///< `--no-progress`
};

/// Adds `--progress` and `--no-progress` to a command.
void add_progress_options(CLI::App& command, ProgressMode& mode);

class ProgressBar {
 public:
  /// `stream` is stderr except in tests; `is_terminal` says whether it is a terminal.
  explicit ProgressBar(ProgressMode mode, std::FILE* stream = stderr);
  ProgressBar(std::FILE* stream, bool enabled, bool is_terminal);
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  ~ProgressBar() { finish(); }

  /// The callback to hand to the library; empty when nothing is shown, so that the library
  /// skips even the calls. Valid while this bar lives.
  ProgressCallback callback();

  /// Ends the display: clears the bar's line on a terminal. Call before printing the result
  /// to stderr or the terminal (the destructor calls it too).
  void finish();

  bool enabled() const { return enabled_; }

 private:
  void update(const Progress& p);
  std::string describe(const Progress& p) const;

  std::FILE* stream_;
  bool enabled_ = false;
  bool terminal_ = false;
  bool drawn_ = false;  ///< a bar line is on the terminal now
  std::string phase_;   ///< the phase of the last call
  std::uint64_t last_done_ = 0, last_total_ = 0;
  std::chrono::steady_clock::time_point last_draw_{};
};

/// load_map with a progress bar of its own, cleared when the map is loaded.
AnyPlMap load_map_showing_progress(const std::filesystem::path& path, ProgressMode mode);

}  // namespace plmap::cli
