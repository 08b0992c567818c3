#pragma once
/// \file
/// RegionImage<d>: everything an evaluation reads once the query's region is known, in one
/// record: the affine map from the S1 element's local coordinates to those of the S2 element the
/// region maps into, that element, and the element's frame in world coordinates (its first
/// corner and the edge vectors to the others).
///
/// Why: evaluate_in_region reads the map's region_target, then region_map (48 bytes, often
/// across two cache lines) and S2's element corners, then three S2 vertices: six or seven cache
/// lines behind a chain of three dependent loads. A record is two adjacent cache lines behind
/// one load, which matters when the region itself comes out of a table look-up (a point
/// locator's cells): the chain of a query is then table -> record instead of table ->
/// region_target -> element corners -> vertices.
///
/// The records are derived, never stored in the map (DESIGN.md §3: what is cheap to derive is
/// built by the consumer that needs it): a locator builds them with its table and reports their
/// bytes as its own memory (128 bytes per region for d = 2). Evaluating through a record gives
/// bit for bit what evaluate_in_region gives: the edge vectors are the differences
/// Surface::world_position forms, and the sums are formed in the same order.

#include <plmap/core/evaluation.hpp>

#include <array>
#include <vector>

namespace plmap {

template <int d>
struct alignas(64) RegionImage {
  /// Local coordinates on the S1 element -> local coordinates on `target` (region_map).
  AffineMap<d> to_target = AffineMap<d>::Zero();
  /// Corner 0 of `target` and the vectors from it to corners 1..d, in world coordinates.
  WorldPoint<d> origin = WorldPoint<d>::Zero();
  std::array<WorldPoint<d>, d> edge{};
  /// The S2 element the region maps into (region_target).
  Index target = invalid_index;
};
static_assert(sizeof(RegionImage<2>) == 128, "a triangle map's record is two cache lines");
static_assert(sizeof(RegionImage<1>) == 64, "a curve map's record is one cache line");

/// The record of every region of `map`, indexed like the regions.
template <int d>
std::vector<RegionImage<d>> region_images(const PlMap<d>& map) {
  const MapData<d>& m = map.stored();
  const Surface<d>& target = map.target();
  std::vector<RegionImage<d>> images(static_cast<std::size_t>(map.region_count()));
  for (Index r = 0; r < map.region_count(); ++r) {
    RegionImage<d>& image = images[static_cast<std::size_t>(r)];
    image.to_target = m.region_map[r];
    image.target = m.region_target[r];
    const ElementCorners<d>& corners = target.element(image.target);
    image.origin = target.vertex(corners[0]);
    // The same subtraction Surface::world_position makes on every call.
    for (int i = 0; i < d; ++i) image.edge[i] = target.vertex(corners[i + 1]) - image.origin;
  }
  return images;
}

/// Xi at a point known to lie in `region`, whose record is `image`: exactly
/// evaluate_in_region(map, region, local).
template <int d>
[[gnu::always_inline]] inline Evaluation<d> evaluate_in_region(const RegionImage<d>& image, Index region,
                                                               const LocalPoint<d>& local) {
  Evaluation<d> e;
  e.in_domain = true;
  e.region = region;
  e.image.element = image.target;
  e.image.local = apply<d>(image.to_target, local);
  // Surface::world_position's sum, term by term in its order.
  WorldPoint<d> x = image.origin;
  for (int i = 0; i < d; ++i) x += e.image.local(i) * image.edge[i];
  e.world = x;
  return e;
}

}  // namespace plmap
