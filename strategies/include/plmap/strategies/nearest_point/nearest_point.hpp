#pragma once
/// \file
/// World point -> nearest point of a surface: the way from a point given in space (a quadrature
/// point of another mesh, a measurement, a point near S1) to a point of S1 that evaluation takes,
/// an element and local coordinates on it.
///
/// Two models of one duck type `nearest(x) -> NearestPoint<d>`:
/// - AabbNearestPoint: CGAL's AABB tree of the elements (Debian libcgal-dev), O(log n) a query;
///   the tree is built once in the constructor, queries are const and may run on many threads;
/// - BruteForceNearestPoint: every element, the reference for tests.
/// Both return the nearest point itself; ties (a point equally near two elements, e.g. on their
/// shared edge) may be attributed to either element.

#include <plmap/core/surface.hpp>

#include <memory>
#include <span>

namespace plmap {

/// The point of a surface nearest to a query point.
template <int d>
struct NearestPoint {
  SurfacePoint<d> point;                         ///< element and local coordinates on it
  WorldPoint<d> world = WorldPoint<d>::Zero();   ///< the nearest point in space
  double distance = 0.0;                         ///< from the query point
};

/// The point of element t nearest to x (local coordinates clamped into the element).
template <int d>
NearestPoint<d> nearest_point_on_element(const Surface<d>& surface, Index t, const WorldPoint<d>& x);

/// Nearest-point queries through CGAL's AABB tree of the surface's elements.
template <int d>
  requires SurfaceDimension<d>
class AabbNearestPoint {
 public:
  /// Builds the tree (O(n log n)); throws plmap::Error for a surface without elements.
  explicit AabbNearestPoint(std::shared_ptr<const Surface<d>> surface);
  ~AabbNearestPoint();
  AabbNearestPoint(AabbNearestPoint&&) noexcept;
  AabbNearestPoint& operator=(AabbNearestPoint&&) noexcept;

  /// The nearest point of the surface to x. Non-finite x throws plmap::Error.
  NearestPoint<d> nearest(const WorldPoint<d>& x) const;
  const Surface<d>& surface() const { return *surface_; }

 private:
  struct Tree;
  std::shared_ptr<const Surface<d>> surface_;
  std::unique_ptr<Tree> tree_;
};

/// The reference: tests every element.
template <int d>
  requires SurfaceDimension<d>
class BruteForceNearestPoint {
 public:
  explicit BruteForceNearestPoint(std::shared_ptr<const Surface<d>> surface) : surface_(std::move(surface)) {}
  NearestPoint<d> nearest(const WorldPoint<d>& x) const;

 private:
  std::shared_ptr<const Surface<d>> surface_;
};

/// nearest(x) for many points on `threads` threads (0: all), in contiguous ranges
/// (parallel_ranges.hpp). Throws plmap::Error if the sizes differ or a point is not finite.
template <int d>
void nearest_points_batch(const AabbNearestPoint<d>& index, std::span<const WorldPoint<d>> points,
                          std::span<NearestPoint<d>> out, unsigned threads = 0);

extern template void nearest_points_batch(const AabbNearestPoint<1>&, std::span<const WorldPoint<1>>,
                                          std::span<NearestPoint<1>>, unsigned);
extern template void nearest_points_batch(const AabbNearestPoint<2>&, std::span<const WorldPoint<2>>,
                                          std::span<NearestPoint<2>>, unsigned);
extern template class AabbNearestPoint<1>;
extern template class AabbNearestPoint<2>;
extern template class BruteForceNearestPoint<1>;
extern template class BruteForceNearestPoint<2>;

}  // namespace plmap
