#pragma once
// finalize(), phase 5: the regions' affine maps, written after the builder is freed. Private to
// the builder.
//
// The closing pass first-touches the whole map while the builder (its nodes, segments and
// buckets) is still alive: that is the peak of a projection. The largest array of the map,
// region_map (48 B per region: 82 MiB on the 200k plane pair), is not needed until finalize
// returns, so the assembly leaves it out. A node's image on another S2 element than the one it is
// stored on needs the weight of the stored element's corner 0, which node_image_local does not
// keep (it holds the weights of corners 1 and 2). Nearly always that weight is 1 minus the two
// kept ones, bit for bit; the assembly keeps it only for the nodes where it is not (their
// "kept omitted weights": 6,385 of the femur pair's 97,549 nodes). With those, the image is
// re-expressed on the region's S2 element exactly as support_local does from the support, and the
// map is the same affine_through of the same values: the maps are bit-identical to those the
// closure computed, while the builder and the region maps are never alive at the same time.
// (One omitted weight per node, as this first kept them, was 0.75 MiB of the femur pair's
// closing pass, on its peak.)

#include "builder_nodes.hpp"

#include <plmap/core/pl_map.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/core/surface.hpp>

#include <optional>
#include <span>
#include <vector>

namespace plmap::detail {

/// The weight a node's support gives to corner 0 of its image element, for a node where
/// 1 - (sum of node_image_local) does not give it back bit for bit.
struct KeptOmittedWeight {
  Index node;  ///< in the map (while a part is assembled: in the part)
  double weight;
};

/// The weight support s gives to corner 0 of its element s.element (+0.0 if that corner is not
/// one of its vertices): what support_local leaves out.
double omitted_image_weight(const Support<2>& s);

/// omitted_image_weight(s) if 1 - (stored(0) + stored(1)) differs from it in any bit (stored:
/// the node's node_image_local), else nothing: what the assembly keeps per node.
std::optional<double> omitted_weight_to_keep(const Support<2>& s, const LocalPoint<2>& stored);

/// Writes m.region_map (empty before) from the regions' corners, targets and the nodes' images,
/// with `kept` (sorted by node) holding the omitted weights that 1 minus the stored two does not
/// give back; on up to `threads` threads.
void write_region_maps(const Surface<2>& s2, std::span<const KeptOmittedWeight> kept, MapData<2>& m, unsigned threads,
                       double spare_room = 0.0);

/// write_region_maps, and the regions' image measures on the way (FinalizeReport::images): per S2
/// element d! times the local measure of the images the maps are made from, summed in region
/// order (directly on one thread; on several, each region's term first and the sums after, so
/// that the bits are the same), and the covered measures as image_measures() sums them.
ImageMeasures write_region_maps_and_measure(const Surface<2>& s1, const Surface<2>& s2,
                                            std::span<const KeptOmittedWeight> kept, MapData<2>& m, unsigned threads,
                                            double spare_room = 0.0);

}  // namespace plmap::detail
