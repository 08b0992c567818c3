#include <plmap/strategies/simplification/weighted_oracles.hpp>

#include <plmap/strategies/simplification/aspect_ratio_oracle.hpp>
#include <plmap/strategies/simplification/hausdorff_oracle.hpp>
#include <plmap/strategies/simplification/long_edge_oracle.hpp>
#include <plmap/strategies/simplification/normal_deviation_oracle.hpp>
#include <plmap/strategies/simplification/self_intersection_veto.hpp>

#include <plmap/core/errors.hpp>

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>

namespace plmap {

namespace {
constexpr std::array<std::string_view, 5> names = {"hausdorff", "aspect-ratio", "long-edge", "normal-deviation",
                                                   "self-intersection"};
}

std::span<const std::string_view> error_oracle_names() { return names; }

WeightedOracles& WeightedOracles::add(std::string_view name, double weight) {
  if (!std::isfinite(weight) || weight < 0.0)
    throw Error(fmt::format("error oracle '{}': the weight must be a finite non-negative number, not {}", name, weight));
  const std::string n(name);
  if (name == "hausdorff") return add(HausdorffOracle{}, weight, n);
  if (name == "aspect-ratio") return add(AspectRatioOracle{}, weight, n);
  if (name == "long-edge") return add(LongEdgeOracle{}, weight, n);
  if (name == "normal-deviation") return add(NormalDeviationOracle{}, weight, n);
  if (name == "self-intersection") return add(SelfIntersectionVeto{}, weight, n);
  throw Error(fmt::format("unknown error oracle '{}' (valid: {})", name, fmt::join(names, ", ")));
}

WeightedOracles& WeightedOracles::add_spec(std::string_view spec) {
  const auto colon = spec.find(':');
  if (colon == std::string_view::npos) return add(spec, 1.0);
  const std::string_view weight_text = spec.substr(colon + 1);
  double weight = 0.0;
  const auto [end, error] = std::from_chars(weight_text.data(), weight_text.data() + weight_text.size(), weight);
  if (error != std::errc() || end != weight_text.data() + weight_text.size() || weight_text.empty())
    throw Error(fmt::format("error oracle '{}': '{}' is not a number", spec, weight_text));
  return add(spec.substr(0, colon), weight);
}

OracleVerdict WeightedOracles::evaluate(const RemovalCandidate& candidate) const {
  OracleVerdict total;
  for (const Member& m : members_) {
    const OracleVerdict v = m.evaluate(candidate);
    if (v.veto) return OracleVerdict::vetoed();
    total.cost += m.weight * v.cost;
  }
  return total;
}

void WeightedOracles::on_applied(const EditableMap& map, const VertexRemovalPlan& plan) {
  for (Member& m : members_)
    if (m.on_applied) m.on_applied(map, plan);
}

std::string WeightedOracles::description() const {
  std::string out;
  for (const Member& m : members_) out += fmt::format("{}{}:{}", out.empty() ? "" : ",", m.name, m.weight);
  return out;
}

}  // namespace plmap
