#pragma once
/// \file
/// Whether any two of a set of planar segments meet other than at a common endpoint (the test of
/// segments_cross_properly over all pairs), by a sweep along x: two segments that share a point
/// have overlapping x-ranges (and y-ranges), so after sorting by the left end of the x-range,
/// the scan of a segment's successors stops at the first one that starts right of its end.
/// The same answer as the all-pairs loop, in O(n log n + pairs whose boxes overlap); editing
/// steps (simplification, quadrilateral smoothing) check every straightened piece this way.

#include <plmap/core/predicates.hpp>

#include <algorithm>
#include <array>
#include <vector>

namespace plmap {

using PlanarSegment = std::array<Eigen::Vector2d, 2>;

/// True if two segments of `segments` share a point other than a common endpoint (see
/// segments_cross_properly). Reorders `segments`.
inline bool any_segments_cross(std::vector<PlanarSegment>& segments) {
  const auto min_x = [](const PlanarSegment& s) { return std::min(s[0].x(), s[1].x()); };
  std::sort(segments.begin(), segments.end(),
            [&min_x](const PlanarSegment& a, const PlanarSegment& b) { return min_x(a) < min_x(b); });
  for (std::size_t a = 0; a < segments.size(); ++a) {
    const PlanarSegment& s = segments[a];
    const double max_x = std::max(s[0].x(), s[1].x());
    const double low_y = std::min(s[0].y(), s[1].y()), high_y = std::max(s[0].y(), s[1].y());
    for (std::size_t b = a + 1; b < segments.size(); ++b) {
      const PlanarSegment& o = segments[b];
      if (min_x(o) > max_x) break;
      if (std::max(o[0].y(), o[1].y()) < low_y || std::min(o[0].y(), o[1].y()) > high_y) continue;
      if (segments_cross_properly(s[0], s[1], o[0], o[1])) return true;
    }
  }
  return false;
}

}  // namespace plmap
