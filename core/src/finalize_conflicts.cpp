// finalize(): S2 edges in conflict (finalize_conflicts.hpp).

#include "finalize_conflicts.hpp"

#include "finalize_closure.hpp"

#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/predicates.hpp>

#include <algorithm>
#include <cstdint>

namespace plmap::detail {

namespace {

/// The builder's segments on element t: inside it and along its three edges.
std::vector<Index> segments_on_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t) {
  std::vector<Index> pieces(where.element_segments[t].begin(), where.element_segments[t].end());
  for (int k = 0; k < 3; ++k) {
    const auto& along = where.edge_segments[in.s1.element_edge(t, k)];
    pieces.insert(pieces.end(), along.begin(), along.end());
  }
  return pieces;
}

/// The nodes inside element t and on its edges (not at its corners).
std::vector<Index> nodes_inside_or_on_edges(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where,
                                            Index t) {
  std::vector<Index> nodes(where.interior_nodes[t].begin(), where.interior_nodes[t].end());
  for (int k = 0; k < 3; ++k) {
    const auto& on_edge = where.edge_nodes[in.s1.element_edge(t, k)];
    nodes.insert(nodes.end(), on_edge.begin(), on_edge.end());
  }
  return nodes;
}

/// x lies on the closed segment pq (exactly); the caller excludes pq's own end nodes.
bool lies_on_segment(const LocalPoint<2>& p, const LocalPoint<2>& q, const LocalPoint<2>& x) {
  return orient2d(p, q, x) == 0 && x.x() >= std::min(p.x(), q.x()) && x.x() <= std::max(p.x(), q.x()) &&
         x.y() >= std::min(p.y(), q.y()) && x.y() <= std::max(p.y(), q.y());
}

}  // namespace

std::vector<Index> conflicting_edges(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t) {
  const std::vector<Index> pieces = segments_on_element(in, where, t);
  std::vector<Index> nodes = nodes_inside_or_on_edges(in, where, t);
  for (int k = 0; k < 3; ++k)
    if (const Index corner = in.node_at_domain_vertex[in.s1.element(t)[k]]; corner != invalid_index) nodes.push_back(corner);
  std::vector<Index> edges;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto& si = in.segments[pieces[i]];
    // a rim edge's conflicts are settled by dropping the rim edges (ElementConflicts::rim_edges),
    // not the S2 edges it meets
    if (si.target_edge == invalid_index) continue;
    const LocalPoint<2> p = node_local(in, si.a, t), q = node_local(in, si.b, t);
    for (std::size_t j = i + 1; j < pieces.size(); ++j) {
      const auto& sj = in.segments[pieces[j]];
      if (sj.target_edge == invalid_index) continue;
      if (segments_cross_properly(p, q, node_local(in, sj.a, t), node_local(in, sj.b, t))) {
        edges.push_back(si.target_edge);
        edges.push_back(sj.target_edge);
      }
    }
    for (Index n : nodes) {
      if (n == si.a || n == si.b) continue;
      if (lies_on_segment(p, q, node_local(in, n, t))) edges.push_back(si.target_edge);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

bool drop_stretch_on_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index e, Index t,
                             DroppedEdges& dropped) {
  std::vector<Index> stretch;
  for (Index s : where.element_segments[t])
    if (in.segments[s].target_edge == e) stretch.push_back(s);
  for (int k = 0; k < 3; ++k)
    for (Index s : where.edge_segments[in.s1.element_edge(t, k)])
      if (in.segments[s].target_edge == e) stretch.push_back(s);
  return dropped.drop_stretch(e, t, stretch);
}

ElementConflicts conflicts_on_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t) {
  ElementConflicts c;
  c.edges = conflicting_edges(in, where, t);
  const std::vector<Index> pieces = segments_on_element(in, where, t);
  const std::vector<Index> nodes = nodes_inside_or_on_edges(in, where, t);
  std::vector<Index> rim, crossing;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto& si = in.segments[pieces[i]];
    if (si.target_edge != invalid_index) continue;
    rim.push_back(pieces[i]);
    const LocalPoint<2> p = node_local(in, si.a, t), q = node_local(in, si.b, t);
    bool crosses = false;
    for (std::size_t j = 0; j < pieces.size() && !crosses; ++j) {
      if (j == i) continue;
      const auto& sj = in.segments[pieces[j]];
      crosses = segments_cross_properly(p, q, node_local(in, sj.a, t), node_local(in, sj.b, t));
    }
    for (std::size_t n = 0; n < nodes.size() && !crosses; ++n) {
      if (nodes[n] == si.a || nodes[n] == si.b) continue;
      crosses = lies_on_segment(p, q, node_local(in, nodes[n], t));
    }
    if (crosses) crossing.push_back(pieces[i]);
  }
  // The rim edges in the way go. If none is, and S2 edges conflict among themselves, their
  // stretches go (in the same round) and the rim stays; else the element failed for another
  // reason (e.g. two nodes that coincide) and all its rim edges go.
  if (!crossing.empty())
    c.rim_edges = std::move(crossing);
  else if (c.edges.empty())
    c.rim_edges = std::move(rim);
  return c;
}

bool drop_conflicts_on_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t,
                               const ElementConflicts& conflicts, DroppedEdges& dropped) {
  bool any = dropped.drop_rim_segments(conflicts.rim_edges);
  for (Index e : conflicts.edges) any = drop_stretch_on_element(in, where, e, t, dropped) || any;
  return any;
}

bool drop_rim_nodes_left_without_rim(const BuilderContents<2>& in, DroppedEdges& dropped) {
  if (!dropped.dropped_rim_segments()) return false;
  // per node: some rim edge ends here (1), a live rim edge does (2)
  std::vector<std::uint8_t> ends(in.nodes.size(), 0);
  const auto segment_count = static_cast<Index>(in.segments.size());
  for (Index s = 0; s < segment_count; ++s) {
    const auto& seg = in.segments[s];
    const bool rim = seg.target_edge == invalid_index, live = !dropped.drops_segment(s, seg.target_edge);
    if (!rim) continue;
    const auto bits = static_cast<std::uint8_t>(live ? 3 : 1);
    ends[static_cast<std::size_t>(seg.a)] |= bits;
    ends[static_cast<std::size_t>(seg.b)] |= bits;
  }
  bool any = false;
  std::vector<char> gone(in.nodes.size(), 0);
  for (std::size_t n = 0; n < in.nodes.size(); ++n) {
    if (in.nodes[n].kind != BuilderNodeKind::rim || dropped.drops_node(static_cast<Index>(n))) continue;
    if ((ends[n] & 1) == 0 || (ends[n] & 2) != 0) continue;  // never had a rim edge, or still has one
    dropped.drop_rim_node(static_cast<Index>(n), in.nodes.size());
    gone[n] = 1;
    any = true;
  }
  if (!any) return false;
  // the pieces of S2 edges that ended at those nodes now end at their last crossing, as where no
  // rim was made
  std::vector<Index> pieces;
  for (Index s = 0; s < segment_count; ++s) {
    const auto& seg = in.segments[s];
    if (!dropped.drops_segment(s, seg.target_edge) &&
        (gone[static_cast<std::size_t>(seg.a)] != 0 || gone[static_cast<std::size_t>(seg.b)] != 0))
      pieces.push_back(s);
  }
  dropped.drop_segments(pieces);
  return any;
}

namespace {

using Piece = std::pair<Index, std::array<Index, 2>>;  // (S2 edge, end nodes)

/// Whether the pieces [first, last) of one S2 edge on one element form one connected chain:
/// grown from the first piece, every piece must come to share an end with what was reached.
bool one_connected_piece(std::span<const Piece> pieces, std::vector<Index>& reached) {
  reached.assign(pieces[0].second.begin(), pieces[0].second.end());
  std::vector<char> in(pieces.size(), 0);
  in[0] = 1;
  for (bool grew = true; grew;) {
    grew = false;
    for (std::size_t q = 1; q < pieces.size(); ++q) {
      if (in[q]) continue;
      const auto& [a, b] = pieces[q].second;
      if (std::find(reached.begin(), reached.end(), a) == reached.end() &&
          std::find(reached.begin(), reached.end(), b) == reached.end())
        continue;
      in[q] = 1;
      reached.push_back(a);
      reached.push_back(b);
      grew = true;
    }
  }
  return std::find(in.begin(), in.end(), 0) == in.end();
}

}  // namespace

bool drop_split_preimages(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where,
                          DroppedEdges& dropped) {
  // Elements are checked in parallel, in fixed chunks, each chunk listing (element, S2 edge) in
  // element order; the edges are then dropped in that order, as a sequential pass would. (Chunks
  // of 512: with 4096 the bones pair of the peer benchmark, 4,200 elements, ran on one thread.)
  constexpr std::size_t chunk = 512;
  const auto n1 = static_cast<std::size_t>(in.s1.element_count());
  std::vector<std::vector<std::pair<Index, Index>>> split((n1 + chunk - 1) / chunk);
  parallel_for_chunks(n1, chunk, in.options.threads, [&](std::size_t begin, std::size_t end) {
    std::vector<Piece> pieces;
    std::vector<Index> reached;
    auto& found = split[begin / chunk];
    for (auto t = static_cast<Index>(begin); t < static_cast<Index>(end); ++t) {
      pieces.clear();
      for (Index s : where.element_segments[t]) pieces.push_back({in.segments[s].target_edge, {in.segments[s].a, in.segments[s].b}});
      for (int k = 0; k < 3; ++k)
        for (Index s : where.edge_segments[in.s1.element_edge(t, k)])
          pieces.push_back({in.segments[s].target_edge, {in.segments[s].a, in.segments[s].b}});
      if (pieces.size() < 2) continue;
      std::sort(pieces.begin(), pieces.end());
      for (std::size_t i = 0, j = 0; i < pieces.size(); i = j) {
        for (j = i + 1; j < pieces.size() && pieces[j].first == pieces[i].first;) ++j;
        if (j - i < 2 || pieces[i].first == invalid_index) continue;  // rim edges: no S2 edge
        if (!one_connected_piece(std::span<const Piece>(pieces.data() + i, j - i), reached))
          found.emplace_back(t, pieces[i].first);
      }
    }
  });
  bool any = false;
  for (const auto& found : split)
    for (const auto& [t, e] : found) any = drop_stretch_on_element(in, where, e, t, dropped) || any;
  return any;
}

}  // namespace plmap::detail
