#pragma once
/// \file
/// The regions of a map as remote intersections: for mortar and contact methods, the pieces
/// T1 ∩ Xi^{-1}(T2) over which integrals of products of S1 and S2 functions are exact.

#include <plmap/core/element_transfer.hpp>
#include <plmap/core/pl_map.hpp>

#include <optional>
#include <vector>

namespace plmap {

/// The image of corner i of region r in the local coordinates of the region's S2 element: the
/// node's image moved there exactly through the shared S2 vertices (the affine map would add
/// rounding, which matters on sliver regions), or the region's map where the image lies on no
/// vertex or edge of that element. (Not value_or: that evaluates the map for every corner.)
template <int d>
LocalPoint<d> corner_image_on_target(const PlMap<d>& map, Index r, int i) {
  const MapData<d>& m = map.stored();
  const Index n = m.region_corners[r][i];
  const std::optional<LocalPoint<d>> moved = transfer_to_element(map.target(), m.node_image(n), m.region_target[r]);
  return moved ? *moved : apply<d>(m.region_map[r], m.node_position[n]);
}

/// One region: a triangle (d = 2) or segment (d = 1) on an S1 element that Xi maps affinely
/// into one S2 element. Corners are listed in the same order on both sides.
template <int d>
struct RemoteIntersection {
  Index region = invalid_index;
  Index domain_element = invalid_index;
  Index target_element = invalid_index;
  std::array<LocalPoint<d>, d + 1> domain_local;
  std::array<LocalPoint<d>, d + 1> target_local;
  std::array<WorldPoint<d>, d + 1> domain_world;
  std::array<WorldPoint<d>, d + 1> target_world;

  /// Length/area of the region on S1 and of its image on S2.
  double domain_measure() const;
  double target_measure() const;
};

/// The remote intersection of one region.
template <int d>
RemoteIntersection<d> remote_intersection(const PlMap<d>& map, Index region);

/// All regions, in region order.
template <int d>
std::vector<RemoteIntersection<d>> remote_intersections(const PlMap<d>& map);

/// Total measure covered on both sides.
struct CoveredMeasure {
  double domain = 0.0;  ///< measure of D on S1 (sum of region measures)
  double target = 0.0;  ///< measure of Xi(D) on S2
};

template <int d>
CoveredMeasure covered_measure(const PlMap<d>& map);

/// covered_measure, and per S2 element the images of its regions in its local coordinates, as d!
/// times their measure: 1 where they cover the element exactly once, more where they overlap.
struct ImageMeasures {
  CoveredMeasure covered;
  std::vector<double> per_target;  ///< one per S2 element
};

/// On `threads` threads (0: all) the regions' measures are computed in parallel and summed in the
/// same order as on one thread: the result is bit-identical for every thread count.
template <int d>
ImageMeasures image_measures(const PlMap<d>& map, unsigned threads = 1);

/// image_measures(map, threads).covered.domain to the last bit, without measuring the images (a
/// fraction of the time: no image is moved onto its region's S2 element).
template <int d>
double covered_domain_measure(const PlMap<d>& map, unsigned threads = 1);

/// What region r adds to image_measures' per_target entry of its S2 element: d! times the
/// measure of its image in that element's local coordinates (its corner images moved there as
/// corner_image_on_target does). A caller that removes a few regions can take these off the
/// sums, measured while the regions exist, instead of measuring the whole map again.
template <int d>
double local_image_measure(const PlMap<d>& map, Index r);

}  // namespace plmap
