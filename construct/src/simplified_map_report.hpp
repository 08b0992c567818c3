#pragma once
// What SimplifyReport says about a finished simplification's map, for surfaces (simplify.cpp)
// and curves (simplify_curve.cpp) alike (construct/src only).

#include <plmap/construct/simplify.hpp>
#include <plmap/core/pl_map.hpp>

#include <algorithm>

namespace plmap::detail {

/// The coarse surface's element and vertex counts, and the Hausdorff error of the map: the
/// largest distance between a node's two places (on the coarse S1 and on the fine S2, which
/// `fine` is), also relative to the diagonal of the fine input's bounding box.
template <int d>
void report_simplified_map(const PlMap<d>& map, const Surface<d>& fine, SimplifyReport& report) {
  report.elements_after = map.domain().element_count();
  report.vertices_after = map.domain().vertex_count();
  for (Index n = 0; n < map.node_count(); ++n)
    report.hausdorff_error = std::max(report.hausdorff_error, (map.node_domain_world(n) - map.node_target_world(n)).norm());
  const double diagonal = (fine.bounding_box_max() - fine.bounding_box_min()).norm();
  report.hausdorff_error_relative = diagonal > 0.0 ? report.hausdorff_error / diagonal : 0.0;
}

}  // namespace plmap::detail
