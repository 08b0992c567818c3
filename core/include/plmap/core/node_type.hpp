#pragma once
/// \file
/// The five kinds of graph nodes of paper section 2.2 (Figure 3).

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
};

inline constexpr int node_type_count = 5;

constexpr std::string_view to_string(NodeType t) {
  switch (t) {
    case NodeType::corner: return "corner";
    case NodeType::touching: return "touching";
    case NodeType::intersection: return "intersection";
    case NodeType::ghost: return "ghost";
    case NodeType::interior: return "interior";
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
  return t == NodeType::touching || t == NodeType::intersection;
}

}  // namespace plmap
