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

void append(const ElementGraph& g, StoredGraph& out) {
  out.element.push_back(g.element);
  out.neighbor_count.insert(out.neighbor_count.end(), g.neighbor_count.begin(), g.neighbor_count.end());
  out.neighbor.insert(out.neighbor.end(), g.neighbor.begin(), g.neighbor.end());
  out.neighbor_edge_kind.insert(out.neighbor_edge_kind.end(), g.kind.begin(), g.kind.end());
  out.edge_node_count.insert(out.edge_node_count.end(), g.edge_node_count.begin(), g.edge_node_count.end());
  out.edge_node.insert(out.edge_node.end(), g.edge_node.begin(), g.edge_node.end());
  out.region_neighbors.insert(out.region_neighbors.end(), g.region_neighbors.begin(), g.region_neighbors.end());
}

StoredGraph join_in_order(std::vector<StoredGraph>& pieces) {
  if (pieces.empty()) return {};
  StoredGraph out = std::move(pieces[0]);
  for (std::size_t k = 1; k < pieces.size(); ++k) {
    const StoredGraph& p = pieces[k];
    out.element.insert(out.element.end(), p.element.begin(), p.element.end());
    out.neighbor_count.insert(out.neighbor_count.end(), p.neighbor_count.begin(), p.neighbor_count.end());
    out.neighbor.insert(out.neighbor.end(), p.neighbor.begin(), p.neighbor.end());
    out.neighbor_edge_kind.insert(out.neighbor_edge_kind.end(), p.neighbor_edge_kind.begin(), p.neighbor_edge_kind.end());
    out.edge_node_count.insert(out.edge_node_count.end(), p.edge_node_count.begin(), p.edge_node_count.end());
    out.edge_node.insert(out.edge_node.end(), p.edge_node.begin(), p.edge_node.end());
    out.region_neighbors.insert(out.region_neighbors.end(), p.region_neighbors.begin(), p.region_neighbors.end());
  }
  return out;
}

}  // namespace plmap::detail
