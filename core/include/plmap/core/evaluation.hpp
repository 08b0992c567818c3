#pragma once
/// \file
/// Evaluating Xi at a point of S1 (paper section 2.3): point location in the element's regions,
/// then one affine map. Point location is a strategy (see strategies/point_location): any type
/// modelling the PointLocator concept below can be plugged in at zero cost.

#include <plmap/core/pl_map.hpp>

#include <concepts>
#include <functional>
#include <span>

namespace plmap {

/// The answer of a point locator: the region that contains the query point, or invalid_index
/// when the point is outside D.
template <int d>
struct RegionLocation {
  Index region = invalid_index;
  bool found() const { return region != invalid_index; }
};

/// A point-location strategy for the regions of one S1 element.
///
/// `locate(map, element, local)` returns the region of `element` containing the point with the
/// given local coordinates. Points on a region boundary may be attributed to either side. A
/// locator may keep mutable state (a random generator, a cache); evaluate_batch gives every
/// thread its own copy.
template <class L, int d>
concept PointLocator = std::copy_constructible<L> &&
    requires(L& locator, const PlMap<d>& map, Index element, const LocalPoint<d>& local) {
      { locator.locate(map, element, local) } -> std::same_as<RegionLocation<d>>;
    };

/// Locators with a per-map table (e.g. a bucket grid) build it in `prepare(map)`; `locate`
/// builds it on first use otherwise. Prepare once before timing or copying a locator to threads.
template <int d, class L>
void prepare_point_locator(L& locator, const PlMap<d>& map) {
  if constexpr (requires { locator.prepare(map); }) locator.prepare(map);
}

/// Xi at one point.
template <int d>
struct Evaluation {
  bool in_domain = false;             ///< false: the point is outside D, the rest is unset
  Index region = invalid_index;       ///< the region of the map containing the point
  SurfacePoint<d> image;              ///< S2 element and local coordinates of Xi(p)
  WorldPoint<d> world = WorldPoint<d>::Zero();  ///< Xi(p) in world coordinates
};

/// Image of a point that is known to lie in `region`. Inlined into the query loops, where it is
/// half of a query's work and the call would copy its result through the stack.
template <int d>
[[gnu::always_inline]] inline Evaluation<d> evaluate_in_region(const PlMap<d>& map, Index region, const LocalPoint<d>& local) {
  Evaluation<d> e;
  e.in_domain = true;
  e.region = region;
  e.image.element = map.stored().region_target[region];
  e.image.local = apply<d>(map.stored().region_map[region], local);
  e.world = map.target().world_position(e.image.element, e.image.local);
  return e;
}

/// A locator that keeps each region's image next to its table (a RegionImage, region_image.hpp)
/// may answer the whole evaluation: `evaluate(map, p)`, returning exactly what
/// evaluate_in_region returns for the region it locates (and {} outside D). evaluate() then
/// calls it instead of locate() + evaluate_in_region, which saves the lookups in the map's
/// arrays behind the located region.
template <class L, int d>
concept EvaluatingPointLocator = PointLocator<L, d> &&
    requires(L& locator, const PlMap<d>& map, const SurfacePoint<d>& p) {
      { locator.evaluate(map, p) } -> std::same_as<Evaluation<d>>;
    };

/// An evaluating locator may also offer `evaluate_prepared(p)`: the same answer on the map of its
/// last prepare(map), without checking per query that its table was built for that map.
/// evaluate_batch prepares its copies once for one map and then calls it; for a certified
/// cell-grid query the check cost as much as a sixth of the query's instructions.
template <class L, int d>
concept PreparedEvaluatingPointLocator = EvaluatingPointLocator<L, d> &&
    requires(L& locator, const PlMap<d>& map, const SurfacePoint<d>& p) {
      locator.prepare(map);
      { locator.evaluate_prepared(p) } -> std::same_as<Evaluation<d>>;
    };

/// Xi(p) for p = (element, local coordinates) using the given point-location strategy.
template <int d, class Locator>
  requires PointLocator<Locator, d>
Evaluation<d> evaluate(const PlMap<d>& map, const SurfacePoint<d>& p, Locator& locator) {
  if constexpr (EvaluatingPointLocator<Locator, d>) {
    return locator.evaluate(map, p);
  } else {
    const RegionLocation<d> loc = locator.locate(map, p.element, p.local);
    if (!loc.found()) return {};
    return evaluate_in_region(map, loc.region, p.local);
  }
}

/// Evaluates many points on `threads` threads (0: all hardware threads). Each thread works on a
/// contiguous chunk with its own copy of `locator`, so the result does not depend on the thread
/// count (for deterministic locators) and no locking happens in the loop.
template <int d, class Locator>
  requires PointLocator<Locator, d>
void evaluate_batch(const PlMap<d>& map, std::span<const SurfacePoint<d>> points,
                    std::span<Evaluation<d>> out, const Locator& locator, unsigned threads = 0);

}  // namespace plmap

#include <plmap/core/evaluation_batch.ipp>
