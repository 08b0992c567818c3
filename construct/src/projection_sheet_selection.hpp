#pragma once
// Normal projection, phase 3: sheet selection. Where the projection is not injective (directions
// tangential to S2, two sheets of S1 whose rays reach the same part of S2), several points of S1
// compete for one point of S2 or one point of S1 for several of S2; of the competitors the
// nearer one (smaller |mu|) is kept, as a vertex preimage keeps the nearest solution:
//  - before the insertion, of the S2 vertex preimages that coincide under the snapping rule;
//  - after finalize, of the regions whose images overlap on S2 (image_overlaps.hpp).

#include "projection_context.hpp"

#include <plmap/construct/projection_result.hpp>
#include <plmap/core/pl_map.hpp>
#include <plmap/core/regions.hpp>

#include <optional>
#include <span>
#include <vector>

namespace plmap::projection {

/// Several S2 vertices can project onto the same point of S1 when the directions are tangential
/// to S2 (a vertical wall over S1, S2 standing on S1): the builder cannot hold two nodes at one
/// point (it throws in finalize), and the map could not be injective anyway. Among preimages that
/// coincide under the snapping rule, the one whose S2 vertex is nearest (smallest |mu|, then the
/// smallest index) is kept; the others are marked here and counted as vertex conflicts, and
/// their edges are reported by the walks. Preimages on the same S1 vertex keep the old rule
/// (first come), which gives the same winner as long as only one of them is nearest.
/// `target_place` holds the places of all preimages (per S2 vertex); returns, per S2 vertex,
/// whether its preimage loses its place.
template <int d>
std::vector<bool> coincident_preimage_losers(const ProjectionContext<d>& ctx,
                                             const std::vector<std::optional<Place<d>>>& target_place);

/// With ProjectionOptions::keep_nearer_sheet: removes the faces of the regions whose images
/// overlap the image of a nearer region (core/face_removal.hpp), counts them in
/// report.occluded_faces and occluded_regions, and brings `images` (image_measures of `map`) up
/// to the map left: covered.domain to the last bit, covered.target and per_target to rounding
/// (the images of the elements the removal changed taken off before it and added back after).
/// The S2 elements in `split_targets` (FinalizeReport::split_targets) are always compared.
template <int d>
void keep_nearer_sheet(PlMap<d>& map, ImageMeasures& images, unsigned threads,
                       ProjectionReport<d>& report, std::span<const Index> split_targets);

}  // namespace plmap::projection
