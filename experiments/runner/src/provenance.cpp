#include <plmap/experiment/build_info.hpp>
#include <plmap/experiment/git_info.hpp>
#include <plmap/experiment/provenance.hpp>

#include <sys/utsname.h>

#include <chrono>
#include <ctime>
#include <fstream>
#include <thread>

namespace plmap::experiment {

namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (!line.starts_with("model name")) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) break;
    auto value = line.substr(colon + 1);
    const auto first = value.find_first_not_of(" \t");
    return first == std::string::npos ? "unknown" : value.substr(first);
  }
  return "unknown";
}

std::string operating_system() {
  utsname u{};
  if (uname(&u) != 0) return "unknown";
  return std::string(u.sysname) + " " + u.release + " " + u.machine;
}

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

}  // namespace

Provenance collect_provenance() {
  Provenance p;
  p.plmap_version = build_info::version;
  p.git_describe = build_info::git_describe;
  p.git_commit = build_info::git_commit;
  p.compiler = std::string(build_info::compiler_id) + " " + build_info::compiler_version;
  p.compiler_flags = build_info::compiler_flags;
  p.build_type = build_info::build_type;
  p.cpu_model = cpu_model();
  p.hardware_threads = std::thread::hardware_concurrency();
  p.operating_system = operating_system();
  p.date = utc_now();
  return p;
}

nlohmann::ordered_json to_json(const Provenance& p) {
  return {{"plmap_version", p.plmap_version}, {"git_describe", p.git_describe},
          {"git_commit", p.git_commit},       {"compiler", p.compiler},
          {"compiler_flags", p.compiler_flags}, {"build_type", p.build_type},
          {"cpu_model", p.cpu_model},         {"hardware_threads", p.hardware_threads},
          {"operating_system", p.operating_system}, {"date", p.date}};
}

}  // namespace plmap::experiment
