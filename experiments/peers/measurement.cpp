// Wall clock, peak memory and stdout silencing of the experiments (measurement.hpp).

#include "measurement.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <fcntl.h>
#include <fstream>
#include <iostream>
#include <string>

namespace plmap::peers {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

namespace {

/// A "VmXXX:  1234 kB" field of /proc/self/status in KiB, or -1.
long status_kib(const std::string& field) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind(field + ":", 0) == 0) return std::stol(line.substr(field.size() + 1));
  return -1;
}

}  // namespace

void Measurement::start() {
  // Writing 5 to clear_refs resets VmHWM to the current resident size (Linux >= 4.0), so the peak
  // seen at stop() belongs to the measured part alone.
  {
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
    clear.flush();
    reset_ok_ = static_cast<bool>(clear);
  }
  baseline_kib_ = status_kib("VmRSS");
  start_cpu_ = process_cpu_seconds();
  start_time_ = now_seconds();
}

void Measurement::stop() {
  seconds_ = now_seconds() - start_time_;
  cpu_seconds_ = process_cpu_seconds() - start_cpu_;
  peak_kib_ = status_kib("VmHWM");
  peak_read_ = peak_kib_ >= 0;
  if (peak_kib_ < 0) {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    peak_kib_ = usage.ru_maxrss;
  }
}

std::optional<double> Measurement::exact_peak_increase_mib() const {
  if (!reset_ok_ || !peak_read_ || baseline_kib_ < 0) return std::nullopt;
  // The baseline is read just after the reset, and reading /proc/self/status may itself touch a
  // page; when the measured part then gives memory back, the kernel's lazily kept high-water mark
  // can end a page below that baseline. No part holds less than nothing above its start.
  return double(std::max(peak_kib_ - baseline_kib_, 0L)) / 1024.0;
}

QuietStdout::QuietStdout() {
  std::cout.flush();
  std::fflush(stdout);
  saved_ = dup(STDOUT_FILENO);
  const int null = open("/dev/null", O_WRONLY);
  if (null >= 0) {
    dup2(null, STDOUT_FILENO);
    close(null);
  }
}

QuietStdout::~QuietStdout() {
  std::cout.flush();
  std::fflush(stdout);
  if (saved_ >= 0) {
    dup2(saved_, STDOUT_FILENO);
    close(saved_);
  }
}

}  // namespace plmap::peers
