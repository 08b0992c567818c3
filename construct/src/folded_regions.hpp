#pragma once
/// \file
/// Regions of a projection map that lie on a folded part of the projection.
///
/// A ghost node is accepted if its ray is unfolded in at least one element at its S1 vertex
/// (walk_acceptance.hpp); in the other elements at that vertex the same ray passes a focal point
/// of their own direction field. No walk enters those elements, but a face there can still close
/// from the ghost node and the pieces that end on the element's edges, and its region would then
/// map points whose rays are folded (area that the ray check finds extra, as `folded_region`:
/// verify/ray_check.hpp judges the region's corners by the same rule). Such a region has a
/// corner whose ray, from the node's point to its image, passes a focal point of the element:
/// those regions are found here and left out of D (remove_regions, core/face_removal.hpp).

#include <plmap/core/pl_map.hpp>
#include <plmap/core/region_clipping.hpp>

#include <span>
#include <vector>

namespace plmap::projection {

/// The regions (sorted, each once) with a corner node whose ray along the interpolated field of
/// its S1 element (`directions`, one per S1 vertex) reaches the node's image only past a focal
/// point of that element (solvers/focal_points.hpp). `focal_free_reach` is each S1 element's
/// focal-free distance, as the projection's set-up computed it (no focal test below it).
template <int d>
  requires SurfaceDimension<d>
std::vector<Index> regions_with_folded_corners(const PlMap<d>& map, std::span<const WorldPoint<d>> directions,
                                               std::span<const double> focal_free_reach, unsigned threads);

/// How the regions with a folded corner (those of regions_with_folded_corners, d = 2) leave D:
/// a region with an unfolded corner is cut along the fold (clip_regions, core/region_clipping.hpp)
/// and keeps the part on its unfolded corners' side. The fold is found on each side from an
/// unfolded corner to a folded one, by bisection with the same test applied to the region's
/// own Xi there, and the cut runs through the last unfolded points, moved back by a hundredth of
/// their sides (so the new nodes are unfolded with a margin). The fold curve is not straight: the
/// part kept may still reach a sliver past it, which the ray check counts as the interpolation
/// at a fold (past_focal_point), not as a region across one. Regions whose corners are all
/// folded, or on which no cut is found, leave whole (`whole`, sorted). `elements` (sorted), if
/// not empty, restricts the search to those S1 elements.
struct FoldCuts {
  std::vector<Index> whole;
  std::vector<RegionClip> clips;
};
FoldCuts fold_cuts(const PlMap<2>& map, std::span<const WorldPoint<2>> directions,
                   std::span<const double> focal_free_reach, unsigned threads, std::span<const Index> elements = {});

extern template std::vector<Index> regions_with_folded_corners<1>(const PlMap<1>&, std::span<const WorldPoint<1>>,
                                                                  std::span<const double>, unsigned);
extern template std::vector<Index> regions_with_folded_corners<2>(const PlMap<2>&, std::span<const WorldPoint<2>>,
                                                                  std::span<const double>, unsigned);

}  // namespace plmap::projection
