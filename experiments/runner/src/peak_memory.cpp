// The peak-memory figure of the in-process steps (peak_memory.hpp).

#include "peak_memory.hpp"

#include <fstream>
#include <string>

namespace plmap::experiment::detail {

namespace {

/// A "VmXXX:  1234 kB" field of /proc/self/status in KiB, or -1.
long status_kib(const std::string& field) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind(field + ":", 0) == 0) return std::stol(line.substr(field.size() + 1));
  return -1;
}

}  // namespace

void PeakMemory::start() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";  // resets VmHWM to the current resident size (Linux >= 4.0)
  clear.flush();
  reset_ = static_cast<bool>(clear);
  baseline_kib_ = status_kib("VmRSS");
}

std::optional<double> PeakMemory::increase_mib() const {
  const long peak = status_kib("VmHWM");
  if (!reset_ || peak < 0 || baseline_kib_ < 0) return std::nullopt;
  return double(peak - baseline_kib_) / 1024.0;
}

}  // namespace plmap::experiment::detail
