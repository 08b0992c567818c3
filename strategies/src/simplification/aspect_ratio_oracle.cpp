#include <plmap/strategies/simplification/aspect_ratio_oracle.hpp>

#include "triangle_geometry.hpp"

namespace plmap {

OracleVerdict AspectRatioOracle::evaluate(const RemovalCandidate& candidate) const {
  double created = 1.0, removed = 1.0;
  for (const auto& t : candidate.plan.new_triangles) created = std::max(created, oracle_detail::aspect_ratio(candidate.map, t));
  for (Index t : candidate.plan.old_triangles)
    removed = std::max(removed, oracle_detail::aspect_ratio(candidate.map, candidate.map.triangle(t)));
  if (!std::isfinite(created)) return OracleVerdict::vetoed();
  return {created - std::min(removed, created + 1e3), false};
}

}  // namespace plmap
