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
};

/// Runs argv[0] (looked up in PATH) with the arguments, waits for it, and returns its exit code
/// and output. Standard input is /dev/null.
ProcessResult run_process(const std::vector<std::string>& argv,
                          const std::filesystem::path& working_directory = {});

}  // namespace plmap::experiment::detail
