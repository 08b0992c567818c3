#pragma once
// How the experiments measure one part of a process: wall clock and the increase of peak
// resident memory over the measured part, and a guard that silences the peers' printing. The one
// implementation (library plmap_peer_measurement) of bench_projection_peers,
// bench_simplification_peers and the experiment runner's in-process steps (simplify, smooth,
// refine).

#include <optional>
#include <string>

namespace plmap::peers {

/// Steady-clock seconds since an arbitrary origin.
double now_seconds();

/// CPU seconds the process has used (all threads). On a loaded machine the wall time of a
/// single-threaded tool includes the time other processes held the core; its CPU time does not.
double process_cpu_seconds();

/// Wall clock, CPU time and memory of the measured part; start() also resets the process's peak
/// memory.
class Measurement {
 public:
  void start();
  void stop();
  double seconds() const { return seconds_; }
  /// CPU seconds of the whole process (all threads) during the measured part: on a machine
  /// shared with other jobs a single-threaded tool's CPU time moves far less than its wall time.
  double cpu_seconds() const { return cpu_seconds_; }
  /// Peak resident memory during the measured part minus the resident memory at start (KiB).
  long peak_increase_kib() const { return peak_kib_ - baseline_kib_; }
  long baseline_kib() const { return baseline_kib_; }
  /// False if the peak could not be reset (then the increase is an upper bound: the peak of the
  /// whole process, input generation included, minus the baseline).
  bool peak_was_reset() const { return reset_ok_; }
  /// The increase in MiB where it is known exactly: the peak was reset (Linux >= 4.0) and
  /// /proc/self/status was readable at start() and stop(); otherwise nothing.
  std::optional<double> exact_peak_increase_mib() const;

 private:
  double start_time_ = 0.0, seconds_ = 0.0, start_cpu_ = 0.0, cpu_seconds_ = 0.0;
  long baseline_kib_ = 0, peak_kib_ = 0;
  bool peak_read_ = false;  ///< VmHWM was read at stop() (not the getrusage fallback)
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

}  // namespace plmap::peers
