#pragma once
// finalize(), phase 5: the regions' affine maps, written after the builder is freed. Private to
// the builder.
//
// The closing pass first-touches the whole map while the builder (its nodes, segments and
// buckets) is still alive: that is the peak of a projection. The largest array of the map,
// region_map (48 B per region: 82 MiB on the 200k plane pair), is not needed until finalize
// returns, so the assembly leaves it out and writes, per node, the one value of the node's image
// that the map does not keep: the weight its support gives to corner 0 of its image element
// (node_image_local holds the weights of corners 1 and 2). With it, the image is re-expressed on
// the region's S2 element exactly as support_local does from the support, and the map is the
// same affine_through of the same values: the maps are bit-identical to those the closure
// computed, while the builder and the region maps are never alive at the same time.

#include "builder_nodes.hpp"

#include <plmap/core/pl_map.hpp>
#include <plmap/core/surface.hpp>

#include <vector>

namespace plmap::detail {

/// The weight support s gives to corner 0 of its element s.element (+0.0 if that corner is not
/// one of its vertices): what support_local leaves out.
double omitted_image_weight(const Support<2>& s);

/// Writes m.region_map (empty before) from the regions' corners, targets and the nodes' images,
/// with `omitted` holding omitted_image_weight per node of m; on up to `threads` threads.
void write_region_maps(const Surface<2>& s2, const std::vector<double>& omitted, MapData<2>& m, unsigned threads,
                       double spare_room = 0.0);

}  // namespace plmap::detail
