#pragma once
// The tools compared by bench_projection_peers: plmap and, when their Debian packages are
// installed, PSurface 2.0 (ContactMapping) and dune-grid-glue 2.9 (ContactMerge). Each tool
// converts the input into its own form first (not measured), then calls `clock.start()`, runs its
// projection, calls `clock.stop()` once its overlaps exist, and only then adds up their measure.

#include "inputs.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace plmap::peers {

/// Wall clock and memory of the measured part; start() also resets the process's peak memory.
class Measurement {
 public:
  void start();
  void stop();
  double seconds() const { return seconds_; }
  /// Peak resident memory during the measured part minus the resident memory at start (KiB).
  long peak_increase_kib() const { return peak_kib_ - baseline_kib_; }
  long baseline_kib() const { return baseline_kib_; }
  /// False if the peak could not be reset (then the increase is an upper bound: the peak of the
  /// whole process, input generation included, minus the baseline).
  bool peak_was_reset() const { return reset_ok_; }

 private:
  double start_time_ = 0.0, seconds_ = 0.0;
  long baseline_kib_ = 0, peak_kib_ = 0;
  bool reset_ok_ = false;
};

/// Sends the process's standard output (std::cout and printf alike) to /dev/null while it lives:
/// the peers print progress, and the benchmark's own output is one JSON line.
class QuietStdout {
 public:
  QuietStdout();
  ~QuietStdout();
  QuietStdout(const QuietStdout&) = delete;
  QuietStdout& operator=(const QuietStdout&) = delete;

 private:
  int saved_ = -1;
};

struct ToolOutcome {
  bool ok = false;
  std::string error;     ///< why the tool did not produce overlaps (exception text)
  double covered = 0.0;  ///< sum of the overlap measures on S1
  long pieces = 0;       ///< regions (plmap), intersection primitives or simplices (peers)
  nlohmann::json details = nlohmann::json::object();
};

template <int d>
ToolOutcome run_plmap(const SurfacePair<d>& input, unsigned threads, Measurement& clock);

#ifdef PLMAP_PEERS_HAVE_PSURFACE
template <int d>
ToolOutcome run_psurface(const SurfacePair<d>& input, Measurement& clock);
#endif

#ifdef PLMAP_PEERS_HAVE_CONTACTMERGE
template <int d>
ToolOutcome run_contactmerge(const SurfacePair<d>& input, Measurement& clock);
#endif

}  // namespace plmap::peers
