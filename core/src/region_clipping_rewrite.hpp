#pragma once
// clip_regions (plmap/core/region_clipping.hpp), the last phase: the map's arrays rewritten with
// the elements the cuts changed. Private to region_clipping.cpp.

#include <plmap/core/pl_map.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace plmap::detail {

/// An element of the clipped map, made by clip_regions from its old nodes, regions and graph and
/// the cuts: what is kept of it until the arrays are rewritten (the old nodes stay in the arrays,
/// moved with them, so only the new ones are kept here).
struct MadeElement {
  Index old_nodes = 0;
  std::vector<LocalPoint<2>> position;  // of all nodes while the element is made, then of the new
  std::vector<NodeType> type;
  std::vector<std::int8_t> location;
  std::vector<SurfacePoint<2>> image;  // of the new nodes
  std::vector<Index> target;           // of the new nodes
  std::vector<Index> neighbor_count;   // per node
  std::vector<std::pair<Index, GraphEdgeKind>> neighbors;  // element-local indices, node by node
  std::array<std::vector<Index>, 3> edge_nodes;            // element-local
  std::vector<std::array<Index, 3>> corners;                            // element-local
  std::vector<std::array<Index, 3>> across;                             // element-local regions
  std::vector<Index> region_target;
  std::vector<AffineMap<2>> region_map;
};

/// The map with the made elements (by element) in place of the old ones: each array's
/// per-element segments move by what the changed elements before them gained or lost, and the
/// changed elements' segments are written from what was made; then the stored graph. On up to
/// `threads` threads; the map is the same for every count.
PlMap<2> rewrite_with_made_elements(PlMap<2>&& map, std::map<Index, MadeElement>& made, unsigned threads);

}  // namespace plmap::detail
