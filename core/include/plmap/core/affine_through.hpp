#pragma once
/// \file
/// The affine map of a region: the one taking its corners' local positions on the S1 element to
/// their images' local coordinates on the region's S2 element. Shared by MapBuilder::finalize and
/// by the algorithms that move nodes after finalize (smoothing), so that both give the same maps.

#include <plmap/core/pl_map.hpp>

#include <Eigen/LU>

#include <array>

namespace plmap {

/// The affine map taking the corners `from` to `to`. Closure triangles can be slivers, whose
/// maps are ill-conditioned; working relative to corner 0 in extended precision keeps the map's
/// values at the corners within rounding of the given images even then.
template <int d>
AffineMap<d> affine_through(const std::array<LocalPoint<d>, d + 1>& from,
                            const std::array<LocalPoint<d>, d + 1>& to) {
  using Real = long double;
  Eigen::Matrix<Real, d, d> f, t;
  for (int k = 1; k <= d; ++k) {
    f.col(k - 1) = (from[k].template cast<Real>() - from[0].template cast<Real>());
    t.col(k - 1) = (to[k].template cast<Real>() - to[0].template cast<Real>());
  }
  const Eigen::Matrix<Real, d, d> linear = t * f.inverse();
  const Eigen::Matrix<Real, d, 1> offset = to[0].template cast<Real>() - linear * from[0].template cast<Real>();
  AffineMap<d> map;
  map.template leftCols<d>() = linear.template cast<double>();
  map.col(d) = offset.template cast<double>();
  return map;
}

}  // namespace plmap
