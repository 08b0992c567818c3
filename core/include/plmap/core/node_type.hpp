#pragma once
/// \file
/// The five kinds of graph nodes of paper section 2.2 (Figure 3), and the two kinds of nodes on
/// the rim of D inside S1 (where the map stops inside an S1 element: a projection reaches its
/// distance limit or a focal point there), which PSurface's maps do not have.

#include <cstdint>
#include <optional>
#include <string_view>

namespace plmap {

enum class NodeType : std::uint8_t {
  /// At a corner of the S1 element; preimage of an S2 vertex.
  corner = 0,
  /// On an edge of the S1 element (not at a corner); preimage of an S2 vertex. d = 2 only.
  touching = 1,
  /// On an edge of the S1 element where the preimage of an S2 edge crosses it. d = 2 only.
  intersection = 2,
  /// At a corner of the S1 element whose image is not an S2 vertex.
  ghost = 3,
  /// In the interior of the S1 element; preimage of an S2 vertex.
  interior = 4,
  /// On an edge of the S1 element (not at a corner) where the rim of D crosses it: the map stops
  /// beyond. Its image is no S2 vertex; node_target is the S2 edge the image lies on, or
  /// invalid_index where it lies inside an S2 element. d = 2 only.
  rim_on_edge = 5,
  /// In the interior of the S1 element, on the rim of D: typically where the preimage of an S2
  /// edge ends because the map stops there (image on that S2 edge, node_target that edge), or a
  /// bend of the rim (image inside an S2 element, node_target invalid_index). d = 2 only.
  rim_inside = 6,
};

inline constexpr int node_type_count = 7;

constexpr std::string_view to_string(NodeType t) {
  switch (t) {
    case NodeType::corner: return "corner";
    case NodeType::touching: return "touching";
    case NodeType::intersection: return "intersection";
    case NodeType::ghost: return "ghost";
    case NodeType::interior: return "interior";
    case NodeType::rim_on_edge: return "rim_on_edge";
    case NodeType::rim_inside: return "rim_inside";
  }
  return "unknown";
}

inline std::optional<NodeType> node_type_from_string(std::string_view s) {
  for (int i = 0; i < node_type_count; ++i)
    if (to_string(static_cast<NodeType>(i)) == s) return static_cast<NodeType>(i);
  return std::nullopt;
}

/// True for the node types that are preimages of S2 vertices.
constexpr bool is_target_vertex_preimage(NodeType t) {
  return t == NodeType::corner || t == NodeType::touching || t == NodeType::interior;
}

/// True for the node types that sit at a corner of their S1 element.
constexpr bool is_at_corner(NodeType t) { return t == NodeType::corner || t == NodeType::ghost; }

/// True for the node types that sit on an edge (not a corner) of their S1 element.
constexpr bool is_on_edge(NodeType t) {
  return t == NodeType::touching || t == NodeType::intersection || t == NodeType::rim_on_edge;
}

/// True for the node types on the rim of D inside S1 (no S2 vertex, no crossing of two edges).
constexpr bool is_on_rim(NodeType t) { return t == NodeType::rim_on_edge || t == NodeType::rim_inside; }

}  // namespace plmap
