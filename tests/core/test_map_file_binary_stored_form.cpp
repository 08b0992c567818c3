// Version 2 of the binary map format stores a triangle map's stored form (PlMap's second
// constructor): the graph arrays only of the elements that keep them, so loading derives and
// compares nothing. Version 1 files (every graph array) still load, converted on the way in.

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/map_file_binary.hpp>
#include <plmap/core/map_validation.hpp>
#include <plmap/verify/generators/subdivision_maps.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace plmap {
namespace {

std::string binary_bytes(const PlMap<2>& map) {
  std::ostringstream out;
  write_binary_map(out, map);
  return std::move(out).str();
}

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::set<std::string> array_names(const std::string& bytes) {
  std::uint64_t table = 0;
  for (int i = 0; i < 8; ++i) table |= std::uint64_t{static_cast<unsigned char>(bytes[16 + i])} << (8 * i);
  const auto toc = nlohmann::json::parse(bytes.substr(32, table));
  std::set<std::string> names;
  for (const auto& a : toc["arrays"]) names.insert(a["name"].get<std::string>());
  return names;
}

/// A builder-made map whose domain has holes: elements partly outside D keep their graph.
const PlMap<2>& map_with_holes() {
  static const auto c = generators::subdivision_map(generators::bumpy_grid(3), 4, 0.1, 3,
                                                    [](Index t, int sub) { return t % 3 == 0 && sub == 0; });
  return *c.map;
}

/// The map's stored arrays without the graph arrays data() may have derived into them.
MapData<2> stored_only(const PlMap<2>& map) {
  MapData<2> m = map.stored();
  m.neighbor_begin.clear();
  m.neighbor.clear();
  m.neighbor_edge_kind.clear();
  m.edge_node_begin.clear();
  m.edge_node.clear();
  m.region_neighbors.clear();
  return m;
}

TEST(MapFileBinaryStoredForm, TriangleMapsStoreOnlyTheGraphOfTheElementsThatKeepIt) {
  const PlMap<2>& map = map_with_holes();
  ASSERT_GT(map.elements_with_stored_graph(), 0);
  ASSERT_LT(map.elements_with_stored_graph(), map.domain().element_count());
  const std::string bytes = binary_bytes(map);
  EXPECT_EQ(bytes[8], 2);  // the version's low byte
  const auto names = array_names(bytes);
  for (const char* derived : {"neighbor_begin", "neighbor", "neighbor_edge_kind", "edge_node_begin", "edge_node",
                              "region_neighbors"})
    EXPECT_EQ(names.count(derived), 0u) << derived;
  for (const char* kept : {"graph_element", "graph_neighbor_begin", "graph_neighbor", "graph_neighbor_edge_kind",
                           "graph_edge_node_begin", "graph_edge_node", "graph_region_neighbors"})
    EXPECT_EQ(names.count(kept), 1u) << kept;
  const auto loaded = std::get<PlMap<2>>(parse_map(bytes, "holes.plmapb"));
  // loading hands the stored form over as written: nothing derived, nothing compared away
  EXPECT_EQ(loaded.derived_bytes(), 0u);
  EXPECT_EQ(loaded.stored_graph(), map.stored_graph());
  EXPECT_EQ(loaded.data(), map.data());
}

TEST(MapFileBinaryStoredForm, Version1FilesAreConvertedOnLoad) {
  // Written by the version 1 writer (main 6180b33) from the text file next to it.
  const std::filesystem::path dir = std::filesystem::path(PLMAP_TEST_DATA_DIR) / "maps";
  const std::string old_bytes = file_bytes(dir / "overlay-tri-version1.plmapb");
  ASSERT_EQ(old_bytes[8], 1);
  ASSERT_EQ(array_names(old_bytes).count("neighbor"), 1u);
  const auto from_v1 = std::get<PlMap<2>>(parse_map(old_bytes, "overlay-tri-version1.plmapb"));
  const auto from_text = std::get<PlMap<2>>(parse_map(file_bytes(dir / "overlay-tri.plmap"), "overlay-tri.plmap"));
  EXPECT_EQ(from_v1.data(), from_text.data());
  // and it is written again as version 2, which loads to the same map
  const std::string new_bytes = binary_bytes(from_v1);
  EXPECT_EQ(new_bytes[8], 2);
  EXPECT_EQ(std::get<PlMap<2>>(parse_map(new_bytes, "again.plmapb")).data(), from_text.data());
}

TEST(MapFileBinaryStoredForm, TheStoredFormRefusesGraphArraysAndDamagedStoredGraphs) {
  const PlMap<2>& map = map_with_holes();
  auto expect_refused = [&](MapData<2> stored, StoredGraph graph, const char* why) {
    try {
      const PlMap<2> bad(map.domain_ptr(), map.target_ptr(), std::move(stored), std::move(graph));
      ADD_FAILURE() << "accepted: " << why;
    } catch (const InvalidMapError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  MapData<2> with_graph = stored_only(map);
  with_graph.region_neighbors.assign(with_graph.region_target.size(), {invalid_index, invalid_index, invalid_index});
  expect_refused(with_graph, map.stored_graph(), "holds graph arrays");
  StoredGraph out_of_order = map.stored_graph();
  std::swap(out_of_order.element.front(), out_of_order.element.back());
  expect_refused(stored_only(map), out_of_order, "out of order");
  StoredGraph short_lists = map.stored_graph();
  short_lists.neighbor.pop_back();
  expect_refused(stored_only(map), short_lists, "stored graph sizes");
  StoredGraph far_neighbor = map.stored_graph();
  far_neighbor.neighbor.front() = map.node_count();
  expect_refused(stored_only(map), far_neighbor, "neighbor index");
}

TEST(MapFileBinaryStoredForm, ValidationNamesTheElementOfAStoredNeighbourFromAnotherElement) {
  const PlMap<2>& map = map_with_holes();
  StoredGraph graph = map.stored_graph();
  const Index t = graph.element.front();
  // a node of another element, in range: only the structural validation can see it
  graph.neighbor.front() = t == 0 ? map.nodes_begin(1) : 0;
  const PlMap<2> bad(map.domain_ptr(), map.target_ptr(), stored_only(map), graph);
  try {
    validate_map_structure(bad, 1);
    FAIL();
  } catch (const InvalidMapError& e) {
    EXPECT_NE(std::string(e.what()).find("at S1 element " + std::to_string(t) + ":"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("which is not another node of element"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plmap
