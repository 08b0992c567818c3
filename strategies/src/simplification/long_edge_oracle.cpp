#include <plmap/strategies/simplification/long_edge_oracle.hpp>

#include "triangle_geometry.hpp"

namespace plmap {

OracleVerdict LongEdgeOracle::evaluate(const RemovalCandidate& candidate) const {
  double longest = 0.0;
  for (const auto& t : candidate.plan.new_triangles)
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (candidate.map.position(t[k]) - candidate.map.position(t[(k + 1) % 3])).squaredNorm());
  return {longest / (candidate.length_scale * candidate.length_scale), false};
}

}  // namespace plmap
