// The peer benchmarks' shared command-line scaffolding (command_line.hpp).

#include "command_line.hpp"

#include <fmt/format.h>

#include <exception>
#include <iostream>
#include <stdexcept>

namespace plmap::peers {

bool ArgumentReader::next() {
  if (index_ + 1 >= argc_) return false;
  name_ = argv_[++index_];
  return true;
}

std::string ArgumentReader::value() {
  if (index_ + 1 >= argc_) throw std::invalid_argument(name_ + " needs a value");
  return argv_[++index_];
}

void ArgumentReader::reject() const { throw std::invalid_argument(fmt::format("unknown argument '{}'", name_)); }

void print_tools(const std::vector<std::string>& tools) {
  for (const auto& tool : tools) std::cout << tool << '\n';
}

void reject_tool(const std::string& tool) {
  throw std::invalid_argument(fmt::format("tool '{}' is not built in (see --list-tools)", tool));
}

void print_result_line(const nlohmann::json& line) { std::cout << line.dump() << std::endl; }

int run_benchmark(const char* program, const std::function<int()>& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return 2;
  }
}

}  // namespace plmap::peers
