// remove_faces (face_removal.hpp): the map on a smaller domain.

#include <plmap/core/errors.hpp>
#include <plmap/core/face_removal.hpp>

#include <fmt/format.h>

#include <cstdint>
#include <vector>

namespace plmap {

namespace {

/// Entry of neighbour b in node a's list (an index into MapData::neighbor), or invalid_index.
template <int d>
Index neighbor_entry(const MapData<d>& m, Index a, Index b) {
  for (Index i = m.neighbor_begin[a]; i < m.neighbor_begin[a + 1]; ++i)
    if (m.neighbor[i] == b) return i;
  return invalid_index;
}

/// Bit k is set when node n lies on local edge k of its element (edge k joins corners k and
/// k + 1, so corner k lies on edges k and k + 2).
std::uint8_t element_edges_through(const MapData<2>& m, Index n) {
  const int k = m.node_location[n];
  if (is_at_corner(m.node_type[n])) return static_cast<std::uint8_t>((1u << k) | (1u << ((k + 2) % 3)));
  if (is_on_edge(m.node_type[n])) return static_cast<std::uint8_t>(1u << k);
  return 0;
}

/// Marks the faces of the named regions (and, where a face lies strictly inside its element, all
/// regions of that element) in `removed`.
template <int d>
void mark_faces(const PlMap<d>& map, std::span<const Index> regions, std::vector<char>& removed,
                FaceRemovalReport& report) {
  const MapData<d>& m = map.data();
  if constexpr (d == 1) {
    for (Index r : regions)
      if (!removed[r]) {
        removed[r] = 1;
        ++report.removed_faces;
      }
  } else {
    std::vector<Index> stack;
    for (Index r0 : regions) {
      if (removed[r0]) continue;
      ++report.removed_faces;
      removed[r0] = 1;
      stack.assign(1, r0);
      bool reaches_boundary = false;
      while (!stack.empty()) {
        const Index r = stack.back();
        stack.pop_back();
        const auto& c = m.region_corners[r];
        for (int i = 0; i < 3; ++i) {
          const Index a = c[(i + 1) % 3], b = c[(i + 2) % 3];
          if (element_edges_through(m, a) & element_edges_through(m, b)) reaches_boundary = true;
          const Index entry = neighbor_entry(m, a, b);
          const bool closure = entry != invalid_index && m.neighbor_edge_kind[entry] == GraphEdgeKind::closure;
          const Index across = m.region_neighbors[r][i];
          if (closure && across != invalid_index && !removed[across]) {
            removed[across] = 1;
            stack.push_back(across);
          }
        }
      }
      if (!reaches_boundary) {
        const Index t = map.node_element(m.region_corners[r0][0]);
        for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r) removed[r] = 1;
        ++report.cleared_elements;
      }
    }
  }
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
PlMap<d> remove_faces(const PlMap<d>& map, std::span<const Index> regions, FaceRemovalReport* report) {
  const MapData<d>& m = map.data();
  const Index nr = map.region_count();
  const Index nt = map.domain().element_count();
  for (Index r : regions)
    if (r < 0 || r >= nr)
      throw InvalidMapError(fmt::format("remove_faces: region {} does not exist (the map has {})", r, nr));

  FaceRemovalReport rep;
  std::vector<char> removed(static_cast<std::size_t>(nr), 0);
  mark_faces(map, regions, removed, rep);

  MapData<d> out;
  out.orientation = m.orientation;
  out.node_begin = m.node_begin;
  out.node_position = m.node_position;
  out.node_type = m.node_type;
  out.node_location = m.node_location;
  out.node_image = m.node_image;
  out.node_target = m.node_target;
  out.edge_node_begin = m.edge_node_begin;
  out.edge_node = m.edge_node;

  // Regions: the kept ones, renumbered in order.
  std::vector<Index> renumbered(static_cast<std::size_t>(nr), invalid_index);
  out.region_begin.assign(static_cast<std::size_t>(nt) + 1, 0);
  out.start_region.assign(static_cast<std::size_t>(nt), invalid_index);
  Index kept = 0;
  for (Index t = 0; t < nt; ++t) {
    for (Index r = m.region_begin[t]; r < m.region_begin[t + 1]; ++r)
      if (!removed[r]) renumbered[r] = kept++;
    out.region_begin[t + 1] = kept;
  }
  rep.removed_regions = nr - kept;
  out.region_corners.reserve(kept);
  out.region_neighbors.reserve(kept);
  out.region_target.reserve(kept);
  out.region_map.reserve(kept);
  for (Index r = 0; r < nr; ++r) {
    if (removed[r]) continue;
    std::array<Index, d + 1> across = m.region_neighbors[r];
    for (Index& g : across) g = g == invalid_index ? invalid_index : renumbered[g];
    out.region_corners.push_back(m.region_corners[r]);
    out.region_neighbors.push_back(across);
    out.region_target.push_back(m.region_target[r]);
    out.region_map.push_back(m.region_map[r]);
  }
  // A walk starts from the old start region if it is kept, else from any region of the element.
  for (Index t = 0; t < nt; ++t) {
    const Index s = m.start_region[t];
    if (s != invalid_index && !removed[s])
      out.start_region[t] = renumbered[s];
    else if (out.region_begin[t] < out.region_begin[t + 1])
      out.start_region[t] = out.region_begin[t];
  }

  // Neighbours: graph edges of d = 2 stay; closure edges (and, for d = 1, the graph edge of a
  // region) stay only while a kept region borders them.
  std::vector<char> keep_entry(m.neighbor.size(), 0);
  if constexpr (d == 2)
    for (std::size_t i = 0; i < m.neighbor.size(); ++i)
      keep_entry[i] = m.neighbor_edge_kind[i] == GraphEdgeKind::target_edge;
  for (Index r = 0; r < nr; ++r) {
    if (removed[r]) continue;
    const auto& c = m.region_corners[r];
    for (int i = 0; i <= d; ++i) {
      const Index a = c[i], b = c[(i + 1) % (d + 1)];
      if (const Index e = neighbor_entry(m, a, b); e != invalid_index) keep_entry[e] = 1;
      if (const Index e = neighbor_entry(m, b, a); e != invalid_index) keep_entry[e] = 1;
    }
  }
  out.neighbor_begin.reserve(m.neighbor_begin.size());
  out.neighbor_begin.push_back(0);
  for (Index n = 0; n + 1 < static_cast<Index>(m.neighbor_begin.size()); ++n) {
    for (Index i = m.neighbor_begin[n]; i < m.neighbor_begin[n + 1]; ++i)
      if (keep_entry[i]) {
        out.neighbor.push_back(m.neighbor[i]);
        out.neighbor_edge_kind.push_back(m.neighbor_edge_kind[i]);
      }
    out.neighbor_begin.push_back(static_cast<Index>(out.neighbor.size()));
  }

  if (report) *report = rep;
  return PlMap<d>(map.domain_ptr(), map.target_ptr(), std::move(out));
}

template PlMap<1> remove_faces<1>(const PlMap<1>&, std::span<const Index>, FaceRemovalReport*);
template PlMap<2> remove_faces<2>(const PlMap<2>&, std::span<const Index>, FaceRemovalReport*);

}  // namespace plmap
