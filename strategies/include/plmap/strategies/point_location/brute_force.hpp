#pragma once
/// \file
/// BruteForce<d>: the reference point locator. Tests every region of the element, O(n) per
/// query, and is the oracle the faster locators are checked against.

#include <plmap/core/evaluation.hpp>
#include <plmap/strategies/point_location/region_geometry.hpp>

namespace plmap::point_location {

template <int d>
  requires SurfaceDimension<d>
struct BruteForce {
  RegionLocation<d> locate(const PlMap<d>& map, Index element, const LocalPoint<d>& p) const {
    return {detail::scan_regions(map.stored(), element, p)};
  }
};

static_assert(PointLocator<BruteForce<1>, 1>);
static_assert(PointLocator<BruteForce<2>, 2>);

}  // namespace plmap::point_location
