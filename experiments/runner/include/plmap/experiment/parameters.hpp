#pragma once
/// \file
/// Parameters of inputs and pipeline steps: a typed value per named key, described by a schema
/// (type, default, bounds, valid choices). One schema per input kind and step kind
/// (schema.hpp) drives validation, defaults, the resolved configuration written with every
/// result row, and sweeps, which replace one parameter's value and validate it again.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace plmap::experiment {

using ParameterValue = std::variant<bool, std::int64_t, double, std::string>;

enum class ParameterType { boolean, integer, real, text, choice };

/// The TOML type name a user sees in error messages ("integer", "string", ...).
std::string type_name(ParameterType type);

struct ParameterSpec {
  std::string name;
  ParameterType type = ParameterType::integer;
  /// Value when the key is absent; nullopt: the key is required (unless `inherits_seed`).
  std::optional<ParameterValue> default_value;
  /// Inclusive bounds for integer and real parameters.
  std::optional<double> min, max;
  /// Valid values of a choice parameter and what they are called in messages ("point locator").
  std::vector<std::string> choices;
  std::string choice_noun;
  /// The parameter only exists when parameter `only_when` has one of `only_when_values`
  /// (e.g. `k` only for `map = "subdivision"`).
  std::string only_when;
  std::vector<std::string> only_when_values;
  /// Absent: take the experiment's seed (so one `[experiment] seed` reseeds everything).
  bool inherits_seed = false;
  std::string doc;
};

/// Resolved values in schema order (every parameter that applies, defaults filled in).
class ParameterSet {
 public:
  void set(const std::string& name, ParameterValue value);
  bool has(const std::string& name) const;
  const ParameterValue& get(const std::string& name) const;  ///< throws std::out_of_range
  bool boolean(const std::string& name) const { return std::get<bool>(get(name)); }
  std::int64_t integer(const std::string& name) const { return std::get<std::int64_t>(get(name)); }
  double real(const std::string& name) const;  ///< integers widen
  const std::string& text(const std::string& name) const { return std::get<std::string>(get(name)); }
  const std::vector<std::pair<std::string, ParameterValue>>& entries() const { return entries_; }

 private:
  std::vector<std::pair<std::string, ParameterValue>> entries_;
};

nlohmann::ordered_json to_json(const ParameterValue& value);
/// The value as it appears in CSV cells and Markdown tables.
std::string to_text(const ParameterValue& value);

}  // namespace plmap::experiment
