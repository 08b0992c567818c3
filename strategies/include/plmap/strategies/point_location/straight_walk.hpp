#pragma once
/// \file
/// StraightWalk: deterministic straight-line walk from the centroid q of the element's start
/// region towards the query point p. In each triangle the walk leaves through the side that the
/// segment q -> p crosses; when the segment runs exactly through a corner and no side qualifies,
/// it leaves through any side that separates p (a visibility step). The answer depends only on
/// the map and the query, never on earlier queries.
///
/// As for BrownFaigleWalk, containment is decided exactly, and leaving D ∩ T through a side
/// without neighbour or exceeding the step budget falls back to scanning the element.

#include <plmap/core/evaluation.hpp>
#include <plmap/strategies/point_location/region_geometry.hpp>

#include <array>

namespace plmap::point_location {

struct StraightWalk {
  RegionLocation<2> locate(const PlMap<2>& map, Index element, const LocalPoint<2>& p) const {
    const MapData<2>& m = map.stored();
    const auto neighbors = map.region_neighbors();
    Index region = m.start_region[element];
    if (region == invalid_index) return {};
    const Index budget = 4 * (m.region_begin[element + 1] - m.region_begin[element]) + 16;
    const auto& start = m.region_corners[region];
    // Any point strictly inside the start region works; rounding of the centroid only changes
    // the path, never the answer.
    const Eigen::Vector2d q =
        (m.node_position[start[0]] + m.node_position[start[1]] + m.node_position[start[2]]) / 3.0;
    for (Index step = 0; step < budget; ++step) {
      const auto& corners = m.region_corners[region];
      const std::array<const Eigen::Vector2d*, 3> corner = {&m.node_position[corners[0]],
                                                           &m.node_position[corners[1]],
                                                           &m.node_position[corners[2]]};
      int exit_side = -1, separating_side = -1;
      for (int side = 0; side < 3; ++side) {
        const Eigen::Vector2d& u = *corner[(side + 1) % 3];
        const Eigen::Vector2d& v = *corner[(side + 2) % 3];
        if (orient2d(u, v, p) >= 0) continue;
        if (separating_side < 0) separating_side = side;
        // Side u -> v (counter-clockwise) is crossed by the segment from q towards p when u is
        // right of the directed line q -> p and v left of it.
        if (orient2d(q, p, u) <= 0 && orient2d(q, p, v) >= 0) {
          exit_side = side;
          break;
        }
      }
      if (separating_side < 0) return {region};
      if (exit_side < 0) exit_side = separating_side;
      const Index next = neighbors[static_cast<std::size_t>(region)][exit_side];
      if (next == invalid_index) break;
      region = next;
    }
    return {detail::scan_regions(m, element, p)};
  }
};

static_assert(PointLocator<StraightWalk, 2>);

}  // namespace plmap::point_location
