#include <plmap/strategies/simplification/normal_deviation_oracle.hpp>

#include "triangle_geometry.hpp"

namespace plmap {

OracleVerdict NormalDeviationOracle::evaluate(const RemovalCandidate& candidate) const {
  const VertexRemovalPlan& plan = candidate.plan;
  double smallest_cosine = 1.0;
  // On a feature line the sides meet at a sharp angle by definition: a new triangle is compared
  // with the removed triangles of its own side only.
  const bool by_sheet = plan.new_triangle_sheet.size() == plan.new_triangles.size() &&
                        plan.old_triangle_sheet.size() == plan.old_triangles.size();
  for (std::size_t n = 0; n < plan.new_triangles.size(); ++n) {
    const Eigen::Vector3d normal = oracle_detail::unit_normal(candidate.map, plan.new_triangles[n]);
    for (std::size_t o = 0; o < plan.old_triangles.size(); ++o) {
      if (by_sheet && plan.new_triangle_sheet[n] != plan.old_triangle_sheet[o]) continue;
      smallest_cosine =
          std::min(smallest_cosine, normal.dot(oracle_detail::unit_normal(candidate.map, candidate.map.triangle(plan.old_triangles[o]))));
    }
  }
  return {1.0 - smallest_cosine, false};
}

}  // namespace plmap
