#pragma once
/// \file
/// The weighted combination of error oracles, and their run-time choice by name.
///
///   WeightedOracles oracles;
///   oracles.add("hausdorff", 1.0).add("aspect-ratio", 0.1).add(MyOracle{}, 2.0);
///
/// The cost of a step is the weighted sum of the members' costs; any member's veto vetoes it.
/// Names (CLI `--oracle NAME[:WEIGHT]`, experiment configs): see error_oracle_names().

#include <plmap/strategies/simplification/error_oracle.hpp>

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace plmap {

class WeightedOracles {
 public:
  /// Adds any ErrorOracle model with the given weight (a copy is kept).
  template <ErrorOracle O>
  WeightedOracles& add(O oracle, double weight = 1.0, std::string name = "custom") {
    auto shared = std::make_shared<O>(std::move(oracle));
    Member m{std::move(name), weight, [shared](const RemovalCandidate& c) { return shared->evaluate(c); }, {}};
    if constexpr (StatefulErrorOracle<O>)
      m.on_applied = [shared](const EditableMap& map, const VertexRemovalPlan& p) { shared->on_applied(map, p); };
    members_.push_back(std::move(m));
    return *this;
  }
  /// Adds the oracle registered under `name` (throws plmap::Error listing the valid names).
  WeightedOracles& add(std::string_view name, double weight = 1.0);
  /// Adds "NAME" or "NAME:WEIGHT" (throws plmap::Error on a malformed weight or unknown name).
  WeightedOracles& add_spec(std::string_view spec);

  OracleVerdict evaluate(const RemovalCandidate& candidate) const;
  void on_applied(const EditableMap& map, const VertexRemovalPlan& plan);

  bool empty() const { return members_.empty(); }
  /// The members' names and weights, in order (curve simplification maps the names that make
  /// sense for curves onto its own costs).
  std::vector<std::pair<std::string, double>> named_weights() const {
    std::vector<std::pair<std::string, double>> out;
    for (const Member& m : members_) out.emplace_back(m.name, m.weight);
    return out;
  }
  /// "hausdorff:1,aspect-ratio:0.1": for reports.
  std::string description() const;

 private:
  struct Member {
    std::string name;
    double weight;
    std::function<OracleVerdict(const RemovalCandidate&)> evaluate;
    std::function<void(const EditableMap&, const VertexRemovalPlan&)> on_applied;
  };
  std::vector<Member> members_;
};
static_assert(StatefulErrorOracle<WeightedOracles>);

/// The names WeightedOracles::add accepts.
std::span<const std::string_view> error_oracle_names();

}  // namespace plmap
