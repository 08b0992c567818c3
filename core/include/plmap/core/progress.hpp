#pragma once
/// \file
/// How long library operations tell their caller how far they have got.
///
/// The library never prints. A long operation (projection, simplification, smoothing, reading
/// or writing a large map) takes an optional `ProgressCallback` and calls it now and then with
/// the phase it is in and how many of that phase's units are done. The command line turns these
/// calls into a progress bar on a terminal; Python or Dune users may log them or ignore them.
///
/// Rules for callers of a callback (the library side):
/// - call it rarely enough not to cost time (at most a few hundred times per phase);
/// - `total` may be 0 when the size of the phase is not known in advance;
/// - call it from the thread that called the operation only (callbacks need not be thread-safe);
/// - within a phase `done` never decreases, and a phase that completes ends with done == total;
/// - the callback may throw to cancel the operation; the exception reaches the caller unchanged
///   and no output file is left half-written.

#include <cstdint>
#include <functional>
#include <string_view>

namespace plmap {

struct Progress {
  std::string_view phase;   ///< short name of the current phase, e.g. "edge walks"
  std::uint64_t done = 0;   ///< units of this phase finished
  std::uint64_t total = 0;  ///< units in this phase, or 0 if unknown
  std::string_view detail = {};  ///< optional: what the current unit is, e.g. a run's parameters
};

using ProgressCallback = std::function<void(const Progress&)>;

/// Calls `callback` if it is set. Keeps the "is there a callback?" test out of algorithms.
inline void report_progress(const ProgressCallback& callback, std::string_view phase, std::uint64_t done,
                            std::uint64_t total, std::string_view detail = {}) {
  if (callback) callback(Progress{phase, done, total, detail});
}

}  // namespace plmap
