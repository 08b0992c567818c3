#pragma once
// The state behind EditableMap, shared by its source files: editable_map.cpp (the state, its
// queries, apply() and the hand-over to MapBuilder), editable_map_removal*.cpp (planning a
// vertex removal phase by phase: removal_planning.hpp lists them) and editable_map_trace.cpp
// (the deferred cut's trace).

#include <plmap/core/editable_map.hpp>
#include "triangle_lists.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <memory>
#include <vector>

namespace plmap {

/// The preimage of one S2 edge: points from the preimage of its smaller-index vertex to the
/// larger. Point i is an endpoint (its vertex is the S2 vertex) or a crossing of the S1 edge
/// `edge` (smaller vertex first) at `edge_parameter`; `target_parameter` is where it lands on
/// the S2 edge (0 at the smaller vertex). Segment i joins points i and i + 1 inside S1 triangle
/// points[i].segment_triangle.
struct EdgePolyline {
  std::vector<PolylinePoint> points;
  int segment_count() const { return static_cast<int>(points.size()) - 1; }
};

struct EditableMap::Impl {
  std::shared_ptr<const Surface<2>> target;
  EditOptions options;

  // S1: vertices share S2's numbering; triangles are never renumbered while editing (removed
  // ones are marked dead, new ones appended).
  std::vector<std::array<Index, 3>> triangles;
  std::vector<char> triangle_live;
  std::vector<char> vertex_live;
  std::vector<std::vector<Index>> vertex_triangles;  ///< live triangles per S1 vertex
  Index live_vertices = 0;
  Index live_triangles = 0;

  // Preimages of S2 vertices that are not S1 vertices: a live triangle and barycentric
  // coordinates strictly inside it.
  std::vector<Index> preimage_triangle;
  std::vector<Eigen::Vector3d> preimage_barycentric;
  // Preimages of S2 vertices that lie on an S1 edge (feature-line removals put them there): the
  // edge (smaller vertex first; invalid if not on an edge) and the parameter from its smaller
  // vertex, strictly between the ends. edge_vertices lists them per S1 edge.
  std::vector<std::array<Index, 2>> preimage_edge;
  std::vector<double> preimage_edge_parameter;
  std::unordered_map<std::uint64_t, std::vector<Index>> edge_vertices;

  std::vector<EdgePolyline> polylines;  ///< per S2 edge
  std::vector<std::uint32_t> polyline_version;  ///< per S2 edge: how often apply() rewrote its polyline
  /// Per S1 triangle: the S2 vertices whose preimage is inside, and the S2 edges with a segment
  /// inside (an edge may be listed more than once). Written when the triangle is made.
  TriangleLists triangle_vertices;
  TriangleLists triangle_edges;
  std::vector<std::pair<Index, std::size_t>> list_sizes;  ///< apply()'s sizes of the new triangles' lists

  static std::uint64_t edge_key(std::array<Index, 2> e) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(e[0])) << 32) | static_cast<std::uint32_t>(e[1]);
  }
  /// The S2 vertices whose preimage lies on the S1 edge e (smaller vertex first).
  const std::vector<Index>* vertices_on_edge(std::array<Index, 2> e) const {
    const auto it = edge_vertices.find(edge_key(e));
    return it == edge_vertices.end() ? nullptr : &it->second;
  }
  bool on_edge(Index w) const { return preimage_edge[w][0] != invalid_index; }

  bool has_edge(Index a, Index b) const {
    for (Index t : vertex_triangles[a]) {
      const auto& c = triangles[t];
      if (c[0] == b || c[1] == b || c[2] == b) return true;
    }
    return false;
  }
};

/// A crossing of an S1 edge (smaller vertex first) by a traced S2 edge: the parameter on the S1
/// edge from its smaller vertex and on the S2 edge from its smaller vertex.
struct TracedCrossing {
  std::array<Index, 2> edge;
  double edge_parameter;
  double target_parameter;
};

/// The deferred cut (editable_map_trace.cpp): per S2 edge, its crossings of S1 edges in order
/// from the preimage of its smaller vertex, traced straight through the final S1 and checked.
/// Throws DeferredCutFailure.
struct EditableMap::Trace {
  static std::vector<std::vector<TracedCrossing>> run(const Impl& s);
};

inline std::array<Index, 2> sorted_pair(Index a, Index b) { return a < b ? std::array{a, b} : std::array{b, a}; }

}  // namespace plmap
