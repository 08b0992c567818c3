#pragma once
/// \file
/// Regions split off faces without a target that the rays do not back.
///
/// finalize() keeps a triangle of a face whose nodes share no S2 element (an unmapped face, or a
/// face at an S1 corner without a node) where its own three corners map into one S2 element
/// (BuilderOptions::split_unmapped_faces). Its corners are nodes, so their images lie on their
/// rays; inside, the affine map interpolates. Between nodes that the walks reached on both sides
/// of a fold or of S2's silhouette along the rays, the triangle can span points whose rays leave
/// that S2 element far from the interpolated image (a grazing ray meets the element's plane far
/// away, or outside the element). Such a region maps area the rays do not: it is named here and
/// left out of D (remove_regions, core/face_removal.hpp).

#include <plmap/core/pl_map.hpp>

#include <span>
#include <vector>

namespace plmap::projection {

/// The regions (sorted, each once) whose target is among `split_targets` (FinalizeReport::
/// split_targets) and at one of whose sample points (the centroid and the midpoints of
/// the sides) the ray along the interpolated field of its S1 element (`directions`, one per S1
/// vertex) meets the plane of the region's S2 element more than half that element's mean edge
/// length away from Xi there, or not at all.
std::vector<Index> split_regions_off_their_rays(const PlMap<2>& map, std::span<const WorldPoint<2>> directions,
                                                std::span<const Index> split_targets, unsigned threads);

}  // namespace plmap::projection
