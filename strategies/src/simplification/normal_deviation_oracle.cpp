#include <plmap/strategies/simplification/normal_deviation_oracle.hpp>

#include "triangle_geometry.hpp"

namespace plmap {

OracleVerdict NormalDeviationOracle::evaluate(const RemovalCandidate& candidate) const {
  double smallest_cosine = 1.0;
  for (const auto& t : candidate.plan.new_triangles) {
    const Eigen::Vector3d n = oracle_detail::unit_normal(candidate.map, t);
    for (Index old : candidate.plan.old_triangles)
      smallest_cosine = std::min(smallest_cosine, n.dot(oracle_detail::unit_normal(candidate.map, candidate.map.triangle(old))));
  }
  return {1.0 - smallest_cosine, false};
}

}  // namespace plmap
