#pragma once
// Internal: running one of experiments/peers' benchmarks in a child process and reading its
// result, shared by the peer_project and peer_simplify steps. The benchmark prints one JSON line
// last (anything before it is the peers' chatter) and exits with 2 and one line on stderr when its
// arguments are wrong or a tool is not built in.

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace plmap::experiment::detail {

/// Throws plmap::Error unless `program` names a file: "STEP: this build has no experiments/peers
/// DESCRIPTION" if it is empty, else one that names the CMake target to build and the environment
/// variable that overrides the path.
void require_peer_benchmark(const std::string& step, const std::string& program, const std::string& description,
                            const std::string& target, const std::string& variable);

/// What the child gave.
struct PeerBenchmarkOutcome {
  bool ok = false;    ///< the result line says the tool produced its result
  std::string error;  ///< why not: the line's "error", or why there is no line (timeout, exit code, stderr)
  nlohmann::ordered_json line;  ///< the result line; null if the child gave none
};

/// Runs argv (argv[0]: the benchmark) with the time limit (seconds) and reads its result line.
/// Exit 2 because a tool is not built in is an Error naming `step`; with `bad_arguments_are_errors`
/// so is every other exit 2 (the step passed something the benchmark refused), otherwise it is a
/// failed run like any other exit code.
PeerBenchmarkOutcome run_peer_benchmark(const std::string& step, const std::vector<std::string>& argv,
                                        double timeout_seconds, bool bad_arguments_are_errors);

/// The number `line[key]`, or null (the benchmarks write NaN, e.g. an undefined error, as null).
nlohmann::ordered_json number_or_null(const nlohmann::ordered_json& line, const char* key);

}  // namespace plmap::experiment::detail
