#pragma once
/// \file
/// Exact containment tests shared by the point locators: is a point in a closed region of an
/// element's graph? Every decision goes through the robust orient2d (d = 2) or an exact double
/// comparison (d = 1), so all locators agree on which regions contain a point; they may differ
/// only in which of several containing regions (a point on a shared side or corner) they return.

#include <plmap/core/pl_map.hpp>
#include <plmap/core/predicates.hpp>

namespace plmap::point_location::detail {

/// Position of corner i of region r (node positions are stored per element in local coords).
template <int d>
inline const LocalPoint<d>& region_corner_position(const MapData<d>& m, Index r, int i) {
  return m.node_position[m.region_corners[r][i]];
}

/// True if the closed triangle r (corners counter-clockwise) contains p.
inline bool region_contains(const MapData<2>& m, Index r, const LocalPoint<2>& p) {
  const auto& c = m.region_corners[r];
  const Eigen::Vector2d& a = m.node_position[c[0]];
  const Eigen::Vector2d& b = m.node_position[c[1]];
  const Eigen::Vector2d& e = m.node_position[c[2]];
  return orient2d(a, b, p) >= 0 && orient2d(b, e, p) >= 0 && orient2d(e, a, p) >= 0;
}

/// True if the closed interval r (corners by increasing position) contains p.
inline bool region_contains(const MapData<1>& m, Index r, const LocalPoint<1>& p) {
  const auto& c = m.region_corners[r];
  return m.node_position[c[0]](0) <= p(0) && p(0) <= m.node_position[c[1]](0);
}

/// The first region of `element` that contains p, scanning all of them; invalid if none does.
template <int d>
Index scan_regions(const MapData<d>& m, Index element, const LocalPoint<d>& p) {
  const Index end = m.region_begin[element + 1];
  for (Index r = m.region_begin[element]; r < end; ++r)
    if (region_contains(m, r, p)) return r;
  return invalid_index;
}

}  // namespace plmap::point_location::detail
