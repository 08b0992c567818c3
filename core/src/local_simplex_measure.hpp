#pragma once
// The sums behind the image measures, on the stored arrays: image_measures and its relatives
// (regions.cpp) and finalize, which measures the images as it writes the region maps
// (finalize_region_maps.cpp), use these, so that both give the same bits.

#include <plmap/core/pl_map.hpp>
#include <plmap/core/surface.hpp>

#include <array>
#include <cmath>
#include <vector>

namespace plmap::detail {

/// d! times the measure of a simplex given in local coordinates: its world measure is this times
/// the measure of its element (the reference element has measure 1/d!).
template <int d>
double local_simplex_measure(const std::array<LocalPoint<d>, d + 1>& x) {
  if constexpr (d == 1) {
    return std::abs(x[1](0) - x[0](0));
  } else {
    const LocalPoint<2> u = x[1] - x[0], v = x[2] - x[0];
    return std::abs(u(0) * v(1) - u(1) * v(0));
  }
}

/// The measure of the regions of S1 element t: their local measures (local_simplex_measure of the
/// corners' positions) summed in region order, scaled once by the element's measure.
template <int d>
double element_regions_measure(const MapData<d>& m, const Surface<d>& s1, Index t) {
  double local = 0.0;
  for (Index r = m.region_begin[t]; r < m.region_begin[t + 1]; ++r) {
    std::array<LocalPoint<d>, d + 1> x;
    for (int i = 0; i <= d; ++i) x[i] = m.node_position[m.region_corners[r][i]];
    local += local_simplex_measure<d>(x);
  }
  return local * s1.element_measure(t);
}

/// ImageMeasures::covered.target from per_target (d! times the local measure covered on each S2
/// element): each nonzero one scaled by its element's measure, added in element order.
template <int d>
double covered_target_measure(const std::vector<double>& per_target, const Surface<d>& s2) {
  double covered = 0.0;
  for (Index t2 = 0; t2 < s2.element_count(); ++t2)
    if (per_target[static_cast<std::size_t>(t2)] != 0.0)
      covered += per_target[static_cast<std::size_t>(t2)] * s2.element_measure(t2);
  return covered;
}

}  // namespace plmap::detail
