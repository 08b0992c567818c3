// One element's graph arrays in the form of StoredGraph (element_graph.hpp).

#include "element_graph.hpp"

#include <utility>

namespace plmap::detail {

namespace {

template <class T>
std::vector<T> slice(const std::vector<T>& v, std::size_t begin, std::size_t end) {
  return std::vector<T>(v.begin() + static_cast<std::ptrdiff_t>(begin), v.begin() + static_cast<std::ptrdiff_t>(end));
}

}  // namespace

ElementGraph stored_element_graph(const StoredGraph& g, const StoredGraphOffsets& at, std::size_t e) {
  ElementGraph out;
  out.element = g.element[e];
  out.neighbor_count = slice(g.neighbor_count, at.node[e], at.node[e + 1]);
  out.neighbor = slice(g.neighbor, at.entry[e], at.entry[e + 1]);
  out.kind = slice(g.neighbor_edge_kind, at.entry[e], at.entry[e + 1]);
  out.edge_node_count = slice(g.edge_node_count, 3 * e, 3 * e + 3);
  out.edge_node = slice(g.edge_node, at.edge_entry[e], at.edge_entry[e + 1]);
  out.region_neighbors = slice(g.region_neighbors, at.region[e], at.region[e + 1]);
  return out;
}

std::optional<ElementGraph> derived_element_graph(const MapData<2>& m, const Surface<2>& target, Index t,
                                                  GraphDerivationScratch& scratch) {
  ElementGraph out;
  out.element = t;
  out.region_neighbors.resize(static_cast<std::size_t>(m.region_begin[t + 1] - m.region_begin[t]));
  if (!derive_region_neighbors(m, t, out.region_neighbors, scratch) ||
      !derive_neighbor_lists(m, target, t, out.region_neighbors, out.neighbor_count, out.neighbor, out.kind, scratch))
    return std::nullopt;
  derive_edge_nodes(m, t, out.edge_node_count, out.edge_node);
  return out;
}

std::vector<Index> list_begins(const ElementGraph& g) {
  std::vector<Index> begin(g.neighbor_count.size() + 1, 0);
  for (std::size_t i = 0; i < g.neighbor_count.size(); ++i) begin[i + 1] = begin[i] + g.neighbor_count[i];
  return begin;
}

namespace {

/// Appends `from`'s entries to `to`.
template <class T>
void append_to(std::vector<T>& to, const std::vector<T>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

/// Appends the per-node, per-side and per-region arrays of one or more element graphs (an
/// ElementGraph or a StoredGraph: `kind` is the one's neighbor kinds, the other's
/// neighbor_edge_kind) to `out`.
template <class Graph>
void append_graph_arrays(const Graph& g, const std::vector<GraphEdgeKind>& kind, StoredGraph& out) {
  append_to(out.neighbor_count, g.neighbor_count);
  append_to(out.neighbor, g.neighbor);
  append_to(out.neighbor_edge_kind, kind);
  append_to(out.edge_node_count, g.edge_node_count);
  append_to(out.edge_node, g.edge_node);
  append_to(out.region_neighbors, g.region_neighbors);
}

}  // namespace

void append(const ElementGraph& g, StoredGraph& out) {
  out.element.push_back(g.element);
  append_graph_arrays(g, g.kind, out);
}

StoredGraph join_in_order(std::vector<StoredGraph>& pieces) {
  if (pieces.empty()) return {};
  StoredGraph out = std::move(pieces[0]);
  for (std::size_t k = 1; k < pieces.size(); ++k) {
    const StoredGraph& p = pieces[k];
    append_to(out.element, p.element);
    append_graph_arrays(p, p.neighbor_edge_kind, out);
  }
  return out;
}

}  // namespace plmap::detail
