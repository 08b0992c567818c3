#pragma once
// The state behind EditableMap, shared by its two source files: editable_map.cpp (the state, its
// queries, apply() and the hand-over to MapBuilder) and editable_map_removal.cpp (planning a
// vertex removal: flatten, merge, relocate, cut, check).

#include <plmap/core/editable_map.hpp>

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

namespace plmap {

/// The preimage of one S2 edge: points from the preimage of its smaller-index vertex to the
/// larger. Point i is an endpoint (vertex[i] is the S2 vertex) or a crossing of the S1 edge
/// edge[i] (smaller vertex first) at parameter edge_parameter[i]; target_parameter[i] is where
/// it lands on the S2 edge (0 at the smaller vertex). Segment i joins points i and i + 1 inside
/// S1 triangle segment_triangle[i].
struct EdgePolyline {
  std::vector<Index> vertex;
  std::vector<std::array<Index, 2>> edge;
  std::vector<double> edge_parameter;
  std::vector<double> target_parameter;
  std::vector<Index> segment_triangle;
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

  std::vector<EdgePolyline> polylines;  ///< per S2 edge
  /// Per S1 triangle: the S2 vertices whose preimage is inside, and the S2 edges with a segment
  /// inside (an edge may be listed more than once).
  std::vector<std::vector<Index>> triangle_vertices;
  std::vector<std::vector<Index>> triangle_edges;

  bool has_edge(Index a, Index b) const {
    for (Index t : vertex_triangles[a]) {
      const auto& c = triangles[t];
      if (c[0] == b || c[1] == b || c[2] == b) return true;
    }
    return false;
  }
};

inline std::array<Index, 2> sorted_pair(Index a, Index b) { return a < b ? std::array{a, b} : std::array{b, a}; }

}  // namespace plmap
