#include <plmap/core/errors.hpp>
#include <plmap/core/map_validation.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include "stored_graph_offsets.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <string>

namespace plmap {

namespace {

using detail::StoredGraphOffsets;

/// The defect of one element; the message starts with the element so that the command line
/// names it whatever the defect is.
[[noreturn]] void fail(Index element, const std::string& what) {
  throw InvalidMapError(fmt::format("map arrays are inconsistent at S1 element {}: {}", element, what));
}

/// Whether `location` is where a node of `type` can sit on a d-simplex: a corner (0..d) for
/// corner and ghost nodes, a local edge (0..2, d = 2 only) for touching and intersection nodes,
/// -1 for interior nodes.
template <int d>
bool location_fits(NodeType type, int location) {
  if (is_at_corner(type)) return location >= 0 && location <= d;
  if (is_on_edge(type)) return d == 2 && location >= 0 && location <= 2;
  if (type == NodeType::rim_inside) return d == 2 && location == -1;
  return type == NodeType::interior && location == -1;
}

/// The S2 entity a node of `type` stands for must exist: an S2 vertex for vertex preimages, an
/// S2 edge for intersection nodes, none (invalid_index) for ghost nodes, the S2 edge the image
/// lies on or none for rim nodes.
template <int d>
bool target_fits(NodeType type, Index target, const Surface<d>& s2) {
  if (is_target_vertex_preimage(type)) return target >= 0 && target < s2.vertex_count();
  if (type == NodeType::intersection) return target >= 0 && target < s2.edge_count();
  if (is_on_rim(type)) return target == invalid_index || (target >= 0 && target < s2.edge_count());
  return type == NodeType::ghost && target == invalid_index;
}

/// Whether local coordinates lie on the reference element up to a generous margin. Nodes and
/// their images lie on their elements up to rounding (verify/ checks that exactly); the bound
/// keeps every derived quantity (world positions, grid cells of the locators, pictures) finite
/// and in range, whatever a file holds. Local coordinates are scale-free, so the margin is too.
template <int d>
bool near_reference_element(const LocalPoint<d>& x) {
  constexpr double margin = 0.25;
  return barycentric_from_local<d>(x).minCoeff() >= -margin;
}

// Only the stored graph needs checking: a triangle map's other elements derive their graph from
// their regions, which gives only indices of their own nodes and regions (nothing is derived
// here). StoredGraphOffsets (stored_graph_offsets.hpp) says where each stored element's part is.

template <int d>
void validate_nodes(const PlMap<d>& map, const StoredGraphOffsets& stored_graph, Index t) {
  const MapData<d>& m = map.stored();
  const Index first = map.nodes_begin(t), end = map.nodes_end(t);
  auto own = [&](Index q) { return q >= first && q < end; };
  for (Index n = first; n < end; ++n) {
    const NodeType type = m.node_type[n];
    if (static_cast<int>(type) >= node_type_count)
      fail(t, fmt::format("node {} has an unknown type {}", n, static_cast<int>(type)));
    if (!location_fits<d>(type, m.node_location[n]))
      fail(t, fmt::format("node {} ({}) has location {}", n, to_string(type), m.node_location[n]));
    if (!target_fits<d>(type, m.node_target[n], map.target()))
      fail(t, fmt::format("node {} ({}) stands for S2 {} {}, which does not exist", n,
                          to_string(type), is_target_vertex_preimage(type) ? "vertex" : "edge",
                          m.node_target[n]));
    const LocalPoint<d>& image_local = m.node_image_local[n];
    if (!m.node_position[n].allFinite() || !image_local.allFinite())
      fail(t, fmt::format("node {} has a non-finite position or image", n));
    if (!near_reference_element<d>(m.node_position[n]))
      fail(t, fmt::format("node {} lies outside its element (local coordinates {})", n,
                          fmt::join(m.node_position[n].data(), m.node_position[n].data() + d, ", ")));
    if (!near_reference_element<d>(image_local))
      fail(t, fmt::format("the image of node {} lies outside its S2 element {} (local coordinates {})",
                          n, m.node_image_element[n],
                          fmt::join(image_local.data(), image_local.data() + d, ", ")));
  }
  auto check_neighbor = [&](Index n, Index q) {
    if (!own(q) || q == n)
      fail(t, fmt::format("node {} lists neighbour {}, which is not another node of element {}", n, q, t));
  };
  if constexpr (d == 1) {
    for (Index n = first; n < end; ++n)
      for (Index j = m.neighbor_begin[n]; j < m.neighbor_begin[n + 1]; ++j) check_neighbor(n, m.neighbor[j]);
  } else {
    const StoredGraph& g = map.stored_graph();
    const std::ptrdiff_t e = StoredGraphOffsets::find(g, t);
    if (e < 0) return;
    const auto i = static_cast<std::size_t>(e);
    std::size_t entry = stored_graph.entry[i];
    for (Index n = first; n < end; ++n) {
      const auto count = static_cast<std::size_t>(g.neighbor_count[stored_graph.node[i] + static_cast<std::size_t>(n - first)]);
      for (std::size_t j = 0; j < count; ++j) check_neighbor(n, g.neighbor[entry++]);
    }
    std::size_t edge = stored_graph.edge_entry[i];
    for (int k = 0; k < 3; ++k)
      for (Index j = 0; j < g.edge_node_count[3 * i + static_cast<std::size_t>(k)]; ++j) {
        const Index q = g.edge_node[edge++];
        if (!own(q))
          fail(t, fmt::format("the node list of local edge {} holds node {} of another element", k, q));
      }
  }
}

template <int d>
void validate_regions(const PlMap<d>& map, const StoredGraphOffsets& stored_graph, Index t) {
  const MapData<d>& m = map.stored();
  // Region neighbours: stored by segment maps, and by the triangle map's elements that store
  // their graph (the others derive them, which gives only symmetric pairs of own regions).
  const std::array<Index, d + 1>* neighbors = nullptr;  // of the element's first region
  if constexpr (d == 1) {
    neighbors = m.region_neighbors.data() + map.regions_begin(t);
  } else {
    const std::ptrdiff_t e = StoredGraphOffsets::find(map.stored_graph(), t);
    if (e >= 0) neighbors = map.stored_graph().region_neighbors.data() + stored_graph.region[static_cast<std::size_t>(e)];
  }
  const Index first_node = map.nodes_begin(t), end_node = map.nodes_end(t);
  const Index first = map.regions_begin(t), end = map.regions_end(t);
  for (Index r = first; r < end; ++r) {
    for (const Index c : m.region_corners[r])
      if (c < first_node || c >= end_node)
        fail(t, fmt::format("region {} has corner node {}, which belongs to another element", r, c));
    if (!m.region_map[r].allFinite()) fail(t, fmt::format("region {} has a non-finite affine map", r));
    if (neighbors == nullptr) continue;
    for (const Index q : neighbors[r - first]) {
      if (q == invalid_index) continue;
      if (q < first || q >= end || q == r)
        fail(t, fmt::format("region {} lists neighbour region {}, which is not another region of "
                            "element {}",
                            r, q, t));
      // Walks step across sides in both directions: the neighbour must list r in return.
      const auto& back = neighbors[q - first];
      if (std::find(back.begin(), back.end(), r) == back.end())
        fail(t, fmt::format("region {} lists neighbour region {}, which does not list it back", r, q));
    }
  }
}

}  // namespace

/// Elements per piece of the parallel validation: the pieces depend only on the element count,
/// and the first defective piece's exception wins (parallel_ranges.hpp), so the element named is
/// the lowest-numbered defective one for every thread count.
constexpr std::size_t elements_per_validation_piece = 4096;

template <int d>
void validate_map_structure(const PlMap<d>& map, unsigned threads) {
  const auto elements = static_cast<std::size_t>(map.domain().element_count());
  const StoredGraphOffsets stored_graph(map.stored(), map.stored_graph());
  parallel_for_chunks(elements, elements_per_validation_piece, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      validate_nodes(map, stored_graph, static_cast<Index>(t));
      validate_regions(map, stored_graph, static_cast<Index>(t));
    }
  });
}

template void validate_map_structure<1>(const PlMap<1>&, unsigned);
template void validate_map_structure<2>(const PlMap<2>&, unsigned);

}  // namespace plmap
