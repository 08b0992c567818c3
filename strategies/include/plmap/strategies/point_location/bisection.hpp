#pragma once
/// \file
/// Bisection: point location on a curve element (d = 1) by binary search over its
/// intervals, O(log n) per query (paper section 2.3).
///
/// Requires what MapBuilder guarantees for d = 1: the regions of an element are stored by
/// increasing position and do not overlap. They need not cover the element: between two
/// intervals (or before the first / after the last) the point is outside D.

#include <plmap/core/evaluation.hpp>
#include <plmap/strategies/point_location/region_geometry.hpp>

namespace plmap::point_location {

struct Bisection {
  RegionLocation<1> locate(const PlMap<1>& map, Index element, const LocalPoint<1>& p) const {
    const MapData<1>& m = map.stored();
    const double x = p(0);
    Index lo = m.region_begin[element], hi = m.region_begin[element + 1];
    if (lo == hi) return {};
    // Find the last interval whose left end is <= x; it is the only candidate that can contain
    // x (a point shared by two touching intervals goes to the right one).
    if (!(left_end(m, lo) <= x)) return {};  // also rejects NaN
    while (hi - lo > 1) {
      const Index mid = lo + (hi - lo) / 2;
      if (left_end(m, mid) <= x)
        lo = mid;
      else
        hi = mid;
    }
    return {x <= m.node_position[m.region_corners[lo][1]](0) ? lo : invalid_index};
  }

 private:
  static double left_end(const MapData<1>& m, Index r) {
    return m.node_position[m.region_corners[r][0]](0);
  }
};

static_assert(PointLocator<Bisection, 1>);

}  // namespace plmap::point_location
