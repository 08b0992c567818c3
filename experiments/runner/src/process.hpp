#pragma once
// Internal: running an external program (tar, gnuplot) without a shell.

#include <filesystem>
#include <string>
#include <vector>

namespace plmap::experiment::detail {

struct ProcessResult {
  int exit_code = -1;   ///< -1 if it could not be started or was killed by a signal
  std::string output;   ///< standard output (if captured)
  std::string errors;   ///< standard error (if captured)
  bool timed_out = false;  ///< killed because it ran longer than the time limit
};

/// Runs argv[0] (looked up in PATH) with the arguments, waits for it, and returns its exit code
/// and output. Standard input is /dev/null. With a positive `time_limit_seconds` the child is
/// killed (SIGKILL) once it has run that long, and the result says timed_out.
ProcessResult run_process(const std::vector<std::string>& argv,
                          const std::filesystem::path& working_directory = {},
                          double time_limit_seconds = 0.0);

}  // namespace plmap::experiment::detail
