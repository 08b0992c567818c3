#pragma once
/// \file
/// Where a result came from: plmap version and git commit (fixed when the build was configured),
/// compiler and flags, CPU, threads, date. Written into every result row.

#include <nlohmann/json.hpp>

#include <string>

namespace plmap::experiment {

struct Provenance {
  std::string plmap_version;
  std::string git_describe;  ///< `git describe --always --dirty`, or "unknown"
  std::string git_commit;    ///< full hash, or "unknown"
  std::string compiler;      ///< e.g. "GNU 12.2.0"
  std::string compiler_flags;
  std::string build_type;
  std::string cpu_model;     ///< first "model name" of /proc/cpuinfo, or "unknown"
  unsigned hardware_threads = 0;
  std::string operating_system;  ///< uname: sysname release machine
  std::string date;              ///< UTC, ISO 8601, when the experiment started
};

/// The provenance of this process, dated now.
Provenance collect_provenance();

nlohmann::ordered_json to_json(const Provenance& provenance);

}  // namespace plmap::experiment
