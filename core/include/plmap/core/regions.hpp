#pragma once
/// \file
/// The regions of a map as remote intersections: for mortar and contact methods, the pieces
/// T1 ∩ Xi^{-1}(T2) over which integrals of products of S1 and S2 functions are exact.

#include <plmap/core/pl_map.hpp>

#include <span>
#include <vector>

namespace plmap {

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

/// The terms image_measures sums, kept so that the measures of the map after a removal of faces
/// (face_removal.hpp: regions go, every other region and every node stays as it was) can be
/// summed again without computing the terms of the elements that kept all their regions.
struct ImageMeasureTerms {
  std::vector<Index> region_begin;     ///< the map's, per S1 element: which elements lost regions
  std::vector<double> region_target;   ///< per region, d! times its image's local measure
  std::vector<double> element_domain;  ///< per S1 element with regions, its regions' measure
};

/// image_measures, keeping its terms in `terms`.
template <int d>
ImageMeasures image_measures(const PlMap<d>& map, unsigned threads, ImageMeasureTerms& terms);

/// image_measures of `smaller`, a map that `terms`' map became by removing regions: only the
/// elements that lost regions have their terms computed again, and the sums run as in
/// image_measures, so the result is the same to the last bit. `terms` becomes smaller's.
template <int d>
ImageMeasures image_measures_after_removal(const PlMap<d>& smaller, unsigned threads, ImageMeasureTerms& terms);

/// image_measures of `changed_map`, a triangle map that `terms`' map became by changing the
/// regions of the S1 elements `changed` (sorted) only (clip_regions, region_clipping.hpp): their
/// terms are computed again, every other element's are moved to its new regions. `terms`
/// becomes changed_map's.
ImageMeasures image_measures_after_change(const PlMap<2>& changed_map, std::span<const Index> changed, unsigned threads,
                                          ImageMeasureTerms& terms);

}  // namespace plmap
