// finalize(), phase 1: bucketing (finalize_buckets.hpp).

#include "finalize_buckets.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace plmap::detail {

template <int d>
void NodesAndSegmentsByPlace<d>::build(const BuilderContents<d>& in, const DroppedEdges& dropped) {
  const Index elements = in.s1.element_count();
  const Index edges = d == 2 ? in.s1.edge_count() : 0;
  const Index node_count = static_cast<Index>(in.nodes.size());
  const Index segment_count = static_cast<Index>(in.segments.size());
  // Intersection nodes belong to the S2 edge that created them, and go with it; rim nodes go
  // with their rim (drop_rim_nodes_left_without_rim).
  auto live = [&](Index n) {
    const auto& node = in.nodes[n];
    return !(d == 2 && node.kind == BuilderNodeKind::intersection && dropped.contains(node.target)) &&
           !dropped.drops_node(n);
  };
  // The four counting sorts are independent (each one pass over all nodes or all segments, too
  // little work per item to cut them further): they run side by side.
  parallel_for_pieces(4, 4, in.options.threads, [&](std::size_t k, std::size_t, std::size_t) {
    switch (k) {
      case 0:
        interior_nodes.build(elements, node_count, [&](Index n) {
          return live(n) && in.nodes[n].place.kind == PlaceKind::element ? in.nodes[n].place.index : -1;
        });
        break;
      case 1:
        edge_nodes.build(edges, node_count, [&](Index n) {
          return live(n) && in.nodes[n].place.kind == PlaceKind::edge ? in.nodes[n].place.index : -1;
        });
        break;
      case 2:
        edge_segments.build(edges, segment_count, [&](Index s) {
          const auto& seg = in.segments[s];
          return !dropped.drops_segment(s, seg.target_edge) && seg.along_edge ? seg.where : -1;
        });
        break;
      default:
        element_segments.build(elements, segment_count, [&](Index s) {
          const auto& seg = in.segments[s];
          return !dropped.drops_segment(s, seg.target_edge) && !seg.along_edge ? seg.where : -1;
        });
    }
  });
  // in fixed chunks of edges, so the error names the same (first) edge for every thread count
  parallel_for_chunks(static_cast<std::size_t>(edges), 4096, in.options.threads, [&](std::size_t begin, std::size_t end) {
    for (auto e = static_cast<Index>(begin); e < static_cast<Index>(end); ++e) {
      const auto list = edge_nodes.group(e);
      std::sort(list.begin(), list.end(),
                [&](Index a, Index b) { return in.nodes[a].place.t() < in.nodes[b].place.t(); });
      for (std::size_t i = 1; i < list.size(); ++i)
        if (in.nodes[list[i]].place.t() == in.nodes[list[i - 1]].place.t())
          throw BuilderError(fmt::format("two nodes at the same point of S1 edge {}", in.nodes[list[i]].place.index));
    }
  });
}

template <int d>
void NodesAndSegmentsByPlace<d>::release() {
  for (Buckets* b : {&interior_nodes, &edge_nodes, &element_segments, &edge_segments}) b->release();
}

template struct NodesAndSegmentsByPlace<1>;
template struct NodesAndSegmentsByPlace<2>;

}  // namespace plmap::detail
