// Running experiments/peers' benchmarks in a child process (peer_benchmark.hpp).

#include "peer_benchmark.hpp"

#include "process.hpp"

#include <plmap/core/errors.hpp>

#include <fmt/format.h>

#include <filesystem>
#include <system_error>

namespace plmap::experiment::detail {

namespace {

/// The last non-empty line of `output` (without its newline).
std::string last_line(const std::string& output) {
  const auto end = output.find_last_not_of('\n');
  if (end == std::string::npos) return {};
  const auto newline = output.rfind('\n', end);
  const std::size_t start = newline == std::string::npos ? 0 : newline + 1;
  return output.substr(start, end + 1 - start);
}

}  // namespace

void require_peer_benchmark(const std::string& step, const std::string& program, const std::string& description,
                            const std::string& target, const std::string& variable) {
  if (program.empty()) throw Error(fmt::format("{}: this build has no experiments/peers {}", step, description));
  if (std::error_code ec; !std::filesystem::is_regular_file(program, ec))
    throw Error(fmt::format("{}: the benchmark {} does not exist (build the target {}, or set {})", step, program,
                            target, variable));
}

PeerBenchmarkOutcome run_peer_benchmark(const std::string& step, const std::vector<std::string>& argv,
                                        double timeout_seconds, bool bad_arguments_are_errors) {
  PeerBenchmarkOutcome outcome;
  const std::string& program = argv.front();
  const auto result = run_process(argv, {}, timeout_seconds);
  if (result.timed_out) {
    outcome.error = fmt::format("timed out after {} s", timeout_seconds);
    return outcome;
  }
  const std::string last = last_line(result.output);
  if (result.exit_code != 0 || last.empty() || last.front() != '{') {
    std::string why = result.errors.empty() ? result.output : result.errors;
    while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
    if (result.exit_code == 2 && why.find("not built in") != std::string::npos)
      throw Error(fmt::format("{}: {} ({} was built without that peer's Debian package)", step, why, program));
    if (result.exit_code == 2 && bad_arguments_are_errors) throw Error(fmt::format("{}: {}", step, why));
    outcome.error = fmt::format("{} exited with {}: {}", program, result.exit_code, why);
    return outcome;
  }
  auto line = nlohmann::ordered_json::parse(last, nullptr, /*allow_exceptions=*/false);
  if (line.is_discarded() || !line.contains("ok") || !line.contains("seconds")) {
    outcome.error = fmt::format("{} printed no result line: {}", program, last.substr(0, 200));
    return outcome;
  }
  outcome.ok = line["ok"].is_boolean() && line["ok"].get<bool>();
  outcome.error = line.contains("error") && line["error"].is_string() ? line["error"].get<std::string>() : "";
  outcome.line = std::move(line);
  return outcome;
}

nlohmann::ordered_json number_or_null(const nlohmann::ordered_json& line, const char* key) {
  return line.is_object() && line.contains(key) && line[key].is_number() ? line[key] : nlohmann::ordered_json(nullptr);
}

}  // namespace plmap::experiment::detail
