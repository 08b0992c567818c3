#include <plmap/strategies/simplification/hausdorff_oracle.hpp>

namespace plmap {

OracleVerdict HausdorffOracle::evaluate(const RemovalCandidate& candidate) const {
  return {candidate.plan.max_node_distance / candidate.length_scale, false};
}

}  // namespace plmap
