#pragma once
// Which tools one of experiments/peers' benchmarks was built with (`--list-tools`), so that a test
// of a peer the build lacks (its Debian package was missing) skips instead of failing.

#include <cstdio>
#include <sstream>
#include <string>

namespace plmap::experiment {

/// Whether `program --list-tools` lists `tool` (one name per line).
inline bool benchmark_has_tool(const std::string& program, const std::string& tool) {
  std::string out;
  if (FILE* pipe = popen((program + " --list-tools").c_str(), "r")) {
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
    pclose(pipe);
  }
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);)
    if (line == tool) return true;
  return false;
}

}  // namespace plmap::experiment
