// finalize(), copying reused elements from a previous map (finalize_reuse.hpp).

#include "finalize_reuse.hpp"

#include "stored_graph_offsets.hpp"

#include <plmap/core/errors.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace plmap::detail {

namespace {

/// Grows an array written in place to hold `needed` values (as assemble_element's make_room).
template <class Array>
void room_for(Array& array, std::size_t needed) {
  if (array.size() < needed) array.resize(std::max(needed, std::min(array.capacity(), array.size() + std::size_t{4096})));
}

}  // namespace

ElementReuse::ElementReuse(const PlMap<2>& previous, std::span<const char> reuse)
    : previous_(previous), reuse_(reuse) {
  const Index n1 = previous.domain().element_count();
  if (static_cast<Index>(reuse.size()) != n1)
    throw BuilderError(fmt::format("reuse flags for {} elements, the domain has {}", reuse.size(), n1));
  const StoredGraph& g = previous.stored_graph();
  stored_position_.assign(static_cast<std::size_t>(n1), -1);
  for (std::size_t e = 0; e < g.element.size(); ++e) stored_position_[static_cast<std::size_t>(g.element[e])] = static_cast<std::ptrdiff_t>(e);
  const StoredGraphOffsets offsets(previous.stored(), g);
  node_ = offsets.node;
  entry_ = offsets.entry;
  edge_entry_ = offsets.edge_entry;
  region_ = offsets.region;
}

void ElementReuse::copy_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t,
                                MapData<2>& part, AssemblyCursor& at) const {
  const MapData<2>& m = previous_.stored();
  const Index nb = m.node_begin[t], ne = m.node_begin[t + 1];
  const Index rb = m.region_begin[t], re = m.region_begin[t + 1];
  // the node count size_part gave element t, and its edge entries (corners at both ends of an edge)
  std::size_t corners = 0, edge_inner = 0;
  for (int k = 0; k < 3; ++k) {
    if (in.node_at_domain_vertex[in.s1.element(t)[k]] != invalid_index) ++corners;
    edge_inner += where.edge_nodes[in.s1.element_edge(t, k)].size();
  }
  const std::size_t ns = static_cast<std::size_t>(ne - nb);
  if (ns != corners + edge_inner + where.interior_nodes[t].size())
    throw BuilderError(fmt::format("element {} to be reused has {} nodes in the previous map, the builder's graph gives it {}", t,
                                   ns, corners + edge_inner + where.interior_nodes[t].size()));
  const auto base = static_cast<Index>(at.nodes);
  const auto shift_node = [&](Index n) { return n - nb + base; };
  const auto rbase = static_cast<Index>(at.regions);
  const auto shift_region = [&](Index r) { return r == invalid_index ? invalid_index : r - rb + rbase; };
  const std::ptrdiff_t stored = stored_position_[static_cast<std::size_t>(t)];
  const StoredGraph& g = previous_.stored_graph();

  // nodes, and their neighbour entries where the previous map stores the element's graph
  const std::size_t first_entry = at.entries, first_edge_node = at.edge_nodes, first_graph_region = at.graph_regions;
  std::size_t entry = stored >= 0 ? entry_[static_cast<std::size_t>(stored)] : 0;
  room_for(part.neighbor_begin, at.graph_nodes + 1 + static_cast<std::size_t>(ne - nb));  // kept if entries are written
  for (Index n = nb; n < ne; ++n) {
    const std::size_t o = at.nodes + static_cast<std::size_t>(n - nb);
    part.node_position[o] = m.node_position[n];
    part.node_type[o] = m.node_type[n];
    part.node_location[o] = m.node_location[n];
    part.node_image_element[o] = m.node_image_element[n];
    part.node_image_local[o] = m.node_image_local[n];
    part.node_target[o] = m.node_target[n];
    if (stored >= 0) {
      const auto count = static_cast<std::size_t>(g.neighbor_count[node_[static_cast<std::size_t>(stored)] + static_cast<std::size_t>(n - nb)]);
      room_for(part.neighbor, at.entries + count);
      room_for(part.neighbor_edge_kind, at.entries + count);
      for (std::size_t j = 0; j < count; ++j, ++entry) {
        part.neighbor[at.entries] = shift_node(g.neighbor[entry]);
        part.neighbor_edge_kind[at.entries++] = g.neighbor_edge_kind[entry];
      }
    }
    part.neighbor_begin[at.graph_nodes + static_cast<std::size_t>(n - nb) + 1] = static_cast<Index>(at.entries);
  }
  at.nodes += ns;
  part.node_begin[at.elements + 1] = static_cast<Index>(at.nodes);

  // nodes along the local edges: the stored ones, or as many placeholders as size_part counted
  std::size_t edge_entry = stored >= 0 ? edge_entry_[static_cast<std::size_t>(stored)] : 0;
  for (int k = 0; k < 3; ++k) {
    std::size_t count = where.edge_nodes[in.s1.element_edge(t, k)].size();
    if (in.node_at_domain_vertex[in.s1.element(t)[k]] != invalid_index) ++count;
    if (in.node_at_domain_vertex[in.s1.element(t)[(k + 1) % 3]] != invalid_index) ++count;
    if (stored >= 0 && static_cast<std::size_t>(g.edge_node_count[3 * static_cast<std::size_t>(stored) + static_cast<std::size_t>(k)]) != count)
      throw BuilderError(fmt::format("element {} to be reused has other nodes on its edge {} in the previous map", t, k));
    room_for(part.edge_node, at.edge_nodes + count);
    for (std::size_t q = 0; q < count; ++q) part.edge_node[at.edge_nodes++] = stored >= 0 ? shift_node(g.edge_node[edge_entry++]) : base;
    part.edge_node_begin[3 * at.elements + static_cast<std::size_t>(k) + 1] = static_cast<Index>(at.edge_nodes);
  }

  // regions
  const auto regions = static_cast<std::size_t>(re - rb);
  room_for(part.region_corners, at.regions + regions);
  room_for(part.region_neighbors, at.graph_regions + regions);
  room_for(part.region_target, at.regions + regions);
  room_for(part.region_map, at.regions + regions);
  for (Index r = rb; r < re; ++r) {
    const std::size_t o = at.regions + static_cast<std::size_t>(r - rb);
    for (int i = 0; i < 3; ++i) part.region_corners[o][i] = shift_node(m.region_corners[r][i]);
    for (int i = 0; i < 3; ++i)
      part.region_neighbors[at.graph_regions][i] =
          stored >= 0 ? shift_region(g.region_neighbors[region_[static_cast<std::size_t>(stored)] + static_cast<std::size_t>(r - rb)][i])
                      : invalid_index;
    ++at.graph_regions;
    part.region_target[o] = m.region_target[r];
    part.region_map[o] = m.region_map[r];
  }
  at.regions += regions;
  part.region_begin[at.elements + 1] = static_cast<Index>(at.regions);
  part.start_region[at.elements] = shift_region(m.start_region[t]);
  // as assemble_element: only an element with neighbour entries keeps its graph
  keep_or_drop_graph_of_element(ns, first_entry, first_edge_node, first_graph_region, part, at);
  ++at.elements;
}

}  // namespace plmap::detail
