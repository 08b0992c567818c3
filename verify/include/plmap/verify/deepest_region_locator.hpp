#pragma once
/// \file
/// A reference point locator for checks and tests, written independently of strategies/: the
/// region of the element in which the point is deepest (largest smallest barycentric weight), or
/// none if the point is outside every region by more than 1e-9 in barycentric weight. O(regions
/// of the element) per query: for checking other locators and evaluations, not for speed.

#include <plmap/core/evaluation.hpp>

namespace plmap {

/// Forward point location written independently of strategies/: the region of the element in
/// which the point is deepest (largest smallest barycentric weight).
template <int d>
struct DeepestRegion {
  RegionLocation<d> locate(const PlMap<d>& map, Index element, const LocalPoint<d>& p) const {
    const auto& m = map.data();
    Index best = invalid_index;
    double best_depth = -1e-9;
    for (Index r = m.region_begin[element]; r < m.region_begin[element + 1]; ++r) {
      const auto& c = m.region_corners[r];
      Barycentric<d> b;
      if constexpr (d == 1) {
        const double a = m.node_position[c[0]](0), z = m.node_position[c[1]](0);
        b(1) = (p(0) - a) / (z - a);
        b(0) = 1.0 - b(1);
      } else {
        const Eigen::Vector2d e1 = m.node_position[c[1]] - m.node_position[c[0]];
        const Eigen::Vector2d e2 = m.node_position[c[2]] - m.node_position[c[0]];
        const Eigen::Vector2d q = p - m.node_position[c[0]];
        const double det = e1.x() * e2.y() - e1.y() * e2.x();
        const double x = (q.x() * e2.y() - q.y() * e2.x()) / det;
        const double y = (e1.x() * q.y() - e1.y() * q.x()) / det;
        b << 1.0 - x - y, x, y;
      }
      if (b.minCoeff() > best_depth) best_depth = b.minCoeff(), best = r;
    }
    return {best};
  }
};

static_assert(PointLocator<DeepestRegion<2>, 2>);

}  // namespace plmap
