#pragma once
// MapBuilder::finalize() for curves and for triangle surfaces: the builder's contents into the
// compact map's arrays. Private to the builder. The phases, each in its own unit:
//   1. bucketing (finalize_buckets): nodes and segments by their place on S1;
//   2. closure (finalize_closure): per S1 element, the plane graph closed into triangles, and
//      each face's S2 element and orientation;
//   3. assembly (finalize_assembly): per block of elements, the closed elements written into
//      that block's part of the flat arrays;
//   4. joining (finalize_joining): the parts concatenated into one map;
//   5. region maps (finalize_region_maps): the regions' affine maps, written once the builder's
//      nodes and segments are freed (the assembly keeps one weight per node for them instead).
// Conflicts (finalize_conflicts) decide which S2 edges are dropped between rounds when
// BuilderOptions::drop_conflicting_edges asks for it. Curves (d = 1) need no closure and no
// parts (finalize_polylines.cpp).

#include "builder_nodes.hpp"

#include <plmap/core/pl_map.hpp>

#include <vector>

namespace plmap::detail {

MapData<1> finalize_polylines(BuilderContents<1>& in, FinalizeReport* report);
class ElementReuse;
/// `reuse`: elements copied from a previous map instead of closed (MapBuilder::finalize_reusing).
/// The assembled map in the builder's own form (finalize_assembly.hpp), and the elements that
/// keep their graph, in order: neighbor_begin holds values for their nodes only.
struct AssembledMap {
  MapData<2> map;
  std::vector<Index> graph_elements;
};
AssembledMap finalize_triangles(BuilderContents<2>& in, FinalizeReport* report, const ElementReuse* reuse = nullptr);

}  // namespace plmap::detail
