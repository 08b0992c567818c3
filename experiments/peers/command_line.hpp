#pragma once
// The command-line scaffolding the peer benchmarks share (bench_projection_peers,
// bench_simplification_peers): `--name value` arguments read in order, `--list-tools`, the one
// JSON result line on stdout, and main()'s contract: any error is one line "PROGRAM: why" on
// stderr and exit code 2 (the experiment runner reads that line and that code).

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace plmap::peers {

/// Walks argv[1..]: `while (args.next())`, then compare `args.name()` and take `args.value()`.
class ArgumentReader {
 public:
  ArgumentReader(int argc, char** argv) : argc_(argc), argv_(argv) {}

  /// Moves to the next argument; false after the last.
  bool next();
  /// The current argument, e.g. "--tool".
  const std::string& name() const { return name_; }
  /// The argument after the current one (consumed); throws std::invalid_argument if none.
  std::string value();
  /// Throws std::invalid_argument "unknown argument '...'" for the current argument.
  [[noreturn]] void reject() const;

 private:
  int argc_;
  char** argv_;
  int index_ = 0;
  std::string name_;
};

/// The `--list-tools` answer: every tool built in, one per line.
void print_tools(const std::vector<std::string>& tools);

/// Throws std::invalid_argument "tool '...' is not built in (see --list-tools)"; the runner
/// recognises the words "not built in" and says which Debian package is missing.
[[noreturn]] void reject_tool(const std::string& tool);

/// The benchmark's result: one JSON object on one line, the last line of stdout.
void print_result_line(const nlohmann::json& line);

/// Runs `body` (which returns the exit code); an exception becomes "PROGRAM: what" on stderr and
/// exit code 2.
int run_benchmark(const char* program, const std::function<int()>& body);

}  // namespace plmap::peers
