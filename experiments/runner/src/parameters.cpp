#include <plmap/experiment/parameters.hpp>

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace plmap::experiment {

std::string type_name(ParameterType type) {
  switch (type) {
    case ParameterType::boolean: return "boolean";
    case ParameterType::integer: return "integer";
    case ParameterType::real: return "number";
    case ParameterType::text: return "string";
    case ParameterType::choice: return "string";
  }
  return "?";
}

void ParameterSet::set(const std::string& name, ParameterValue value) {
  for (auto& [key, v] : entries_)
    if (key == name) {
      v = std::move(value);
      return;
    }
  entries_.emplace_back(name, std::move(value));
}

bool ParameterSet::has(const std::string& name) const {
  for (const auto& e : entries_)
    if (e.first == name) return true;
  return false;
}

const ParameterValue& ParameterSet::get(const std::string& name) const {
  for (const auto& e : entries_)
    if (e.first == name) return e.second;
  throw std::out_of_range("no parameter " + name);
}

double ParameterSet::real(const std::string& name) const {
  const ParameterValue& v = get(name);
  if (const auto* i = std::get_if<std::int64_t>(&v)) return double(*i);
  return std::get<double>(v);
}

nlohmann::ordered_json to_json(const ParameterValue& value) {
  return std::visit([](const auto& v) { return nlohmann::ordered_json(v); }, value);
}

std::string to_text(const ParameterValue& value) {
  struct Visitor {
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(std::int64_t i) const { return std::to_string(i); }
    // Shortest text that reads back to the same double.
    std::string operator()(double x) const { return fmt::format("{}", x); }
    std::string operator()(const std::string& s) const { return s; }
  };
  return std::visit(Visitor{}, value);
}

}  // namespace plmap::experiment
