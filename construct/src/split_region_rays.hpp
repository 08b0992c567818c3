#pragma once
/// \file
/// Regions split off faces at a corner without a node that the rays do not back.
///
/// finalize() keeps a triangle of a face whose nodes share no S2 element where its own three
/// corners map into one S2 element (BuilderOptions::split_unmapped_faces). For a face at an S1
/// corner without a node (its ray found no admissible image, at a fold or past S2's silhouette
/// along the rays), those corners are nodes that the walks reached around that corner, and
/// nothing inserted between them vouches for the inside: a triangle between nodes on both sides
/// of the silhouette maps points whose rays meet S2 far from the interpolated image, or miss it.
/// Such a region maps area the rays do not; it is named here and left out of D
/// (remove_regions, core/face_removal.hpp).

#include <plmap/core/pl_map.hpp>

#include <span>
#include <vector>

namespace plmap::projection {

/// Of the regions in `candidates` (sorted; FinalizeReport::regions_split_off_outside_faces), those
/// at one of whose sample points (the centroid and the midpoints of the sides) the ray along the
/// interpolated field of its S1 element (`directions`, one per S1 vertex) meets the plane of the
/// region's S2 element more than half that element's mean edge length away from Xi there, not
/// at all, or only past a focal point of the element's field (`focal_free_reach`: each S1
/// element's focal-free distance, as the projection's set-up computed it) (sorted).
std::vector<Index> split_regions_off_their_rays(const PlMap<2>& map, std::span<const WorldPoint<2>> directions,
                                                std::span<const double> focal_free_reach,
                                                std::span<const Index> candidates, unsigned threads);

}  // namespace plmap::projection
