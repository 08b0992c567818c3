#pragma once
// d! times the measure of a simplex given in local coordinates, the term the image measures sum
// (regions.cpp) and finalize sums when it measures the images as it writes the region maps
// (finalize_region_maps.cpp): one formula, so that both give the same bits.

#include <plmap/core/pl_map.hpp>

#include <array>
#include <cmath>

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

}  // namespace plmap::detail
