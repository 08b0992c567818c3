#pragma once
// Small maps for the file-format tests: hand-made ones that depend only on PlMap's constructor,
// and builder-made ones with intersection nodes, closure edges and ghost nodes.

#include <plmap/core/map_builder.hpp>
#include <plmap/core/pl_map.hpp>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace plmap::test_maps {

/// The identity map of one triangle onto itself, written out by hand.
inline PlMap<2> hand_made_triangle() {
  auto s = std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
      std::vector<ElementCorners<2>>{{0, 1, 2}});
  MapData<2> m;
  m.node_begin = {0, 3};
  m.node_position = {{0, 0}, {1, 0}, {0, 1}};
  m.node_type = {NodeType::corner, NodeType::corner, NodeType::corner};
  m.node_location = {0, 1, 2};
  m.node_image_element = {0, 0, 0};
  m.node_image_local = {{0, 0}, {1, 0}, {0, 1}};
  m.node_target = {0, 1, 2};
  m.neighbor_begin = {0, 2, 4, 6};
  m.neighbor = {1, 2, 2, 0, 0, 1};
  m.neighbor_edge_kind.assign(6, GraphEdgeKind::target_edge);
  m.edge_node_begin = {0, 2, 4, 6};
  m.edge_node = {0, 1, 1, 2, 2, 0};
  m.region_begin = {0, 1};
  m.region_corners = {{0, 1, 2}};
  m.region_neighbors = {{invalid_index, invalid_index, invalid_index}};
  m.region_target = {0};
  AffineMap<2> identity = AffineMap<2>::Zero();
  identity.leftCols<2>().setIdentity();
  m.region_map = {identity};
  m.start_region = {0};
  return PlMap<2>(s, s, std::move(m));
}

/// The identity map of one segment onto itself, written out by hand.
inline PlMap<1> hand_made_segment() {
  auto s = std::make_shared<const Surface<1>>(std::vector<WorldPoint<1>>{{0, 0}, {1, 0}},
                                              std::vector<ElementCorners<1>>{{0, 1}});
  MapData<1> m;
  m.node_begin = {0, 2};
  m.node_position = {LocalPoint<1>(0.0), LocalPoint<1>(1.0)};
  m.node_type = {NodeType::corner, NodeType::corner};
  m.node_location = {0, 1};
  m.node_image_element = {0, 0};
  m.node_image_local = {LocalPoint<1>(0.0), LocalPoint<1>(1.0)};
  m.node_target = {0, 1};
  m.neighbor_begin = {0, 1, 2};
  m.neighbor = {1, 0};
  m.neighbor_edge_kind = {GraphEdgeKind::target_edge, GraphEdgeKind::target_edge};
  m.region_begin = {0, 1};
  m.region_corners = {{0, 1}};
  m.region_neighbors = {{invalid_index, invalid_index}};
  m.region_target = {0};
  AffineMap<1> identity;
  identity << 1.0, 0.0;
  m.region_map = {identity};
  m.start_region = {0};
  return PlMap<1>(s, s, std::move(m));
}

/// The unit square split along one diagonal (S1) mapped onto the same square split along the
/// other diagonal (S2): the S2 diagonal crosses the S1 diagonal, so the map has intersection
/// nodes, closure edges and four regions.
inline PlMap<2> builder_square_flip() {
  const std::vector<WorldPoint<2>> square{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  auto s1 = std::make_shared<const Surface<2>>(square,
                                               std::vector<ElementCorners<2>>{{0, 1, 2}, {0, 2, 3}});
  auto s2 = std::make_shared<const Surface<2>>(square,
                                               std::vector<ElementCorners<2>>{{0, 1, 3}, {1, 2, 3}});
  MapBuilder<2> b(s1, s2);
  for (Index v = 0; v < 4; ++v) b.add_vertex_preimage_at_vertex(v, v);
  for (auto [a, c] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{2, 3}, std::pair{0, 3}}) {
    b.add_edge(s2->find_edge(a, c));
  }
  const EdgeCrossing across{s1->find_edge(0, 2), 0.5};
  b.add_edge(s2->find_edge(1, 3), std::span<const EdgeCrossing>(&across, 1));
  return std::move(b).finalize();
}

/// A polyline of three segments mapped onto one of two segments with a different vertex
/// spacing: ghost nodes where S1 vertices are not on S2 vertices.
inline PlMap<1> builder_polyline() {
  auto s1 = std::make_shared<const Surface<1>>(
      std::vector<WorldPoint<1>>{{0, 0}, {1, 0}, {2, 0}, {3, 0}},
      std::vector<ElementCorners<1>>{{0, 1}, {1, 2}, {2, 3}});
  auto s2 = std::make_shared<const Surface<1>>(
      std::vector<WorldPoint<1>>{{0, 0.5}, {1.7, 0.5}, {3, 0.5}},
      std::vector<ElementCorners<1>>{{0, 1}, {1, 2}});
  MapBuilder<1> b(s1, s2);
  b.add_vertex_preimage_at_vertex(0, 0);
  b.add_vertex_preimage(1, SurfacePoint<1>{1, LocalPoint<1>(0.7)});
  b.add_vertex_preimage_at_vertex(2, 3);
  const VertexCrossing first{1};
  b.add_edge(0, std::span<const VertexCrossing>(&first, 1));
  const VertexCrossing second{2};
  b.add_edge(1, std::span<const VertexCrossing>(&second, 1));
  return std::move(b).finalize();
}

inline std::filesystem::path scratch_directory(const std::string& name) {
  const auto dir = std::filesystem::path(PLMAP_TEST_BINARY_DIR) / "map_file_scratch" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

}  // namespace plmap::test_maps
