#include "progress_bar.hpp"

#include <fmt/format.h>

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>

namespace plmap::cli {

namespace {

using Clock = std::chrono::steady_clock;

/// Redraws of the terminal bar are at least this far apart (ten a second).
constexpr auto terminal_interval = std::chrono::milliseconds(100);
/// Lines on a pipe within one phase are at least this far apart.
constexpr auto line_interval = std::chrono::seconds(1);
constexpr int bar_width = 24;

}  // namespace

void add_progress_options(CLI::App& command, ProgressMode& mode) {
  CLI::Option* on = command.add_flag_callback(
      "--progress", [&mode] { mode = ProgressMode::always; },
      "Show progress on stderr even when it is not a terminal (plain lines)");
  CLI::Option* off = command.add_flag_callback(
      "--no-progress", [&mode] { mode = ProgressMode::never; }, "Show no progress (default: a bar when stderr is a terminal)");
  on->excludes(off);
}

ProgressBar::ProgressBar(ProgressMode mode, std::FILE* stream)
    : ProgressBar(stream, mode == ProgressMode::always || (mode == ProgressMode::automatic && isatty(fileno(stream))),
                  isatty(fileno(stream)) != 0) {}

ProgressBar::ProgressBar(std::FILE* stream, bool enabled, bool is_terminal)
    : stream_(stream), enabled_(enabled), terminal_(is_terminal) {}

ProgressCallback ProgressBar::callback() {
  if (!enabled_) return {};
  return [this](const Progress& p) { update(p); };
}

std::string ProgressBar::describe(const Progress& p) const {
  std::string text;
  if (p.total == 0) {
    text = fmt::format("{}: {}", p.phase, p.done);
  } else {
    const double fraction = std::min(1.0, double(p.done) / double(p.total));
    const int filled = static_cast<int>(fraction * bar_width);
    text = terminal_ ? fmt::format("{}: {:3.0f}% [{}{}]", p.phase, 100.0 * fraction, std::string(filled, '#'),
                                   std::string(bar_width - filled, ' '))
                     : fmt::format("{}: {:.0f}% ({}/{})", p.phase, 100.0 * fraction, p.done, p.total);
  }
  if (!p.detail.empty()) text += fmt::format(" {}", p.detail);
  if (terminal_) {
    // A line wider than the terminal wraps, and "\r" would then redraw only its last part.
    winsize size{};
    const std::size_t columns =
        ioctl(fileno(stream_), TIOCGWINSZ, &size) == 0 && size.ws_col > 1 ? size.ws_col : 80;
    if (text.size() >= columns) text.resize(columns - 1);
  }
  return text;
}

void ProgressBar::update(const Progress& p) {
  const Clock::time_point now = Clock::now();
  const bool new_phase = p.phase != phase_;
  const bool phase_done = p.total > 0 && p.done >= p.total;
  if (new_phase) phase_.assign(p.phase);
  // Same state as last shown (a phase reported twice as complete): nothing to draw.
  const bool same = !new_phase && p.done == last_done_ && p.total == last_total_;
  last_done_ = p.done;
  last_total_ = p.total;
  if (same) return;
  if (terminal_) {
    if (!new_phase && !phase_done && now - last_draw_ < terminal_interval) return;
    // \r and "erase to end of line": the new text may be shorter than the old.
    std::fputs(fmt::format("\r{}\x1b[K", describe(p)).c_str(), stream_);
    drawn_ = true;
  } else {
    if (!new_phase && !phase_done && now - last_draw_ < line_interval) return;
    std::fputs((describe(p) + "\n").c_str(), stream_);
  }
  std::fflush(stream_);
  last_draw_ = now;
}

void ProgressBar::finish() {
  if (drawn_) {
    std::fputs("\r\x1b[K", stream_);
    std::fflush(stream_);
    drawn_ = false;
  }
  phase_.clear();
  last_done_ = last_total_ = 0;
}

AnyPlMap load_map_showing_progress(const std::filesystem::path& path, ProgressMode mode) {
  ProgressBar bar(mode);
  return load_map(path, bar.callback());
}

}  // namespace plmap::cli
