#pragma once
// Internal: the increase of the process's peak resident memory over one step (Linux: resetting
// VmHWM through /proc/self/clear_refs, then reading VmHWM and VmRSS from /proc/self/status).
// Elsewhere, or if the reset is refused, no figure is given.

#include <optional>

namespace plmap::experiment::detail {

class PeakMemory {
 public:
  /// Resets the peak to the current resident size and remembers that size.
  void start();
  /// MiB the peak rose above the resident size at start(), or nothing if unknown.
  std::optional<double> increase_mib() const;

 private:
  long baseline_kib_ = -1;
  bool reset_ = false;
};

}  // namespace plmap::experiment::detail
