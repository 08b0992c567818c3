#pragma once
/// \file
/// Where normal projection is not injective: two sheets of S1 whose rays reach the same part of
/// S2 (a steep hill in S1 whose flanks fan out over the plain around it, two bodies one above the
/// other). Vertex preimages already keep the nearest solution, but faces formed from ghost nodes
/// and boundary entries on the farther sheet can still map onto S2 elements that the nearer sheet
/// covers, and the map would then fail the coverage invariant (images overlap on S2).
///
/// farther_overlapping_regions() finds those faces' regions: per S2 element, if the images of its
/// regions add up to more or less than the element (less: D's boundary bounds part of the
/// preimage, and one sheet can reach over itself there), or come from S1 elements that are not connected
/// (two sheets each covering part of the element), it compares them pairwise, and of two overlapping
/// regions names the one whose points lie farther from their images. project() then removes
/// them (remove_regions, core/face_removal.hpp): of the two sheets the nearer one stays, as for a vertex
/// preimage.

#include <plmap/core/pl_map.hpp>
#include <plmap/core/regions.hpp>

#include <span>
#include <vector>

namespace plmap::projection {

/// Tolerances as verify's coverage check uses them (VerifyOptions): an overlap counts when it
/// exceeds `measure_tolerance` times the smaller image and what corners off by
/// `position_tolerance` (local coordinates) along the smaller boundary could explain.
struct OverlapTolerances {
  double measure_tolerance = 1e-8;
  double position_tolerance = 1e-9;
};

/// The regions (sorted, each once) whose images overlap the image of a region whose points lie
/// nearer to their images (ties: the larger region index is named). `images` are the map's
/// image_measures (core/regions.hpp), which project() computes anyway for the covered measures:
/// only S2 elements whose images add up to more or less than the element, or whose regions lie
/// on S1 elements that are not edge-connected, are looked at. The connectivity search runs on up
/// to `threads` threads (0: all); the result does not depend on their number. The S2 elements
/// in `also_compared` are compared whatever their images add up to: those where the argument of
/// the tiling does not hold (FinalizeReport::split_targets).
template <int d>
  requires SurfaceDimension<d>
std::vector<Index> farther_overlapping_regions(const PlMap<d>& map, const ImageMeasures& images,
                                               const OverlapTolerances& tolerances = {}, unsigned threads = 1,
                                               std::span<const Index> also_compared = {});

extern template std::vector<Index> farther_overlapping_regions<1>(const PlMap<1>&, const ImageMeasures&,
                                                                  const OverlapTolerances&, unsigned,
                                                                  std::span<const Index>);
extern template std::vector<Index> farther_overlapping_regions<2>(const PlMap<2>&, const ImageMeasures&,
                                                                  const OverlapTolerances&, unsigned,
                                                                  std::span<const Index>);

}  // namespace plmap::projection
