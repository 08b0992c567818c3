// A triangle map stores its graph arrays (neighbour lists with edge kinds, edge arrays, region
// neighbours) only on the elements its regions do not tile, and derives the rest on demand: a
// map handed its full arrays keeps them where they do not follow from the regions (a corrupt
// file, a hand-made map), so data() gives them back unchanged.

#include <plmap/core/pl_map.hpp>
#include <plmap/verify/generators/random_maps.hpp>
#include <plmap/verify/generators/rc_generators.hpp>
#include <plmap/verify/generators/subdivision_maps.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <thread>
#include <vector>

namespace plmap {
namespace {

/// The map handed over its full arrays again: what the constructor keeps, and what data() gives.
PlMap<2> rebuilt(const PlMap<2>& map, MapData<2> data) {
  return PlMap<2>(map.domain_ptr(), map.target_ptr(), std::move(data));
}

std::size_t full_bytes(const MapData<2>& m) {
  auto b = [](const auto& v) { return v.size() * sizeof(v[0]); };
  return b(m.node_begin) + b(m.node_position) + b(m.node_type) + b(m.node_location) +
         b(m.node_image_element) + b(m.node_image_local) + b(m.node_target) + b(m.neighbor_begin) + b(m.neighbor) + b(m.neighbor_edge_kind) +
         b(m.edge_node_begin) + b(m.edge_node) + b(m.region_begin) + b(m.region_corners) +
         b(m.region_neighbors) + b(m.region_target) + b(m.region_map) + b(m.start_region);
}

/// What every fully covered map must satisfy: nothing of the graph stored, the derivation gives
/// back the builder's arrays exactly, and the stored form is smaller by the graph arrays.
void check_derives_everything(const PlMap<2>& map) {
  const MapData<2> full = map.data();
  RC_ASSERT(map.elements_with_stored_graph() == 0);
  const PlMap<2> again = rebuilt(map, full);
  RC_ASSERT(again.elements_with_stored_graph() == 0);
  RC_ASSERT(again.stored().neighbor.empty());
  RC_ASSERT(again.stored().region_neighbors.empty());
  RC_ASSERT(again.data() == full);
  RC_ASSERT(again.memory_bytes() < full_bytes(full));
}

RC_GTEST_PROP(DerivedGraph, RefinementMapsDeriveTheBuildersGraph, ()) {
  const auto c = *rc::gen::scale(0.6, generators::refinement_maps<2>());
  check_derives_everything(*c.map);
}

RC_GTEST_PROP(DerivedGraph, OverlayMapsGiveBackTheBuildersGraph, ()) {
  // Intersection and ghost nodes, graph edges through S1 vertices; elements partly outside D
  // keep their graph. Whatever is stored or derived, handing data() over again gives it back.
  const auto c = *rc::gen::scale(0.6, generators::overlay_maps<2>());
  const MapData<2> full = c.map->data();
  const PlMap<2> again = rebuilt(*c.map, full);
  RC_ASSERT(again.data() == full);
  // the builder stores the graph of every element its regions do not tile, the comparison only
  // of those whose graph the derivation does not give back
  RC_ASSERT(again.elements_with_stored_graph() <= c.map->elements_with_stored_graph());
  RC_ASSERT(again.memory_bytes() < full_bytes(full));
  RC_CLASSIFY(c.map->elements_with_stored_graph() == 0, "graph derived on every element");
}

TEST(DerivedGraph, SubdivisionMapStoresNoGraphAndLessThanHalfTheGraphBytes) {
  const auto s1 = generators::bumpy_grid(4);
  const auto c = generators::subdivision_map(s1, 4, 0.1, 7);
  const MapData<2> full = c.map->data();
  EXPECT_EQ(c.map->elements_with_stored_graph(), 0);
  EXPECT_EQ(c.map->data(), full);
  // The graph arrays are about a third of the full form; all of them are derived.
  auto b = [](const auto& v) { return v.size() * sizeof(v[0]); };
  const std::size_t graph = b(full.neighbor_begin) + b(full.neighbor) + b(full.neighbor_edge_kind) +
                            b(full.edge_node_begin) + b(full.edge_node) + b(full.region_neighbors);
  EXPECT_LE(c.map->memory_bytes(), full_bytes(full) - graph);
  EXPECT_EQ(c.map->derived_bytes(), graph);
}

TEST(DerivedGraph, HolesInTheDomainKeepEveryArray) {
  // Dropped sub-triangles leave parts of elements outside D; whatever is stored or derived there,
  // data() gives back the builder's arrays.
  const auto s1 = generators::bumpy_grid(3);
  const auto c = generators::subdivision_map(s1, 4, 0.1, 3, [](Index t, int sub) { return (t + sub) % 5 == 0; });
  const MapData<2> full = c.map->data();
  const PlMap<2> again = rebuilt(*c.map, full);
  EXPECT_EQ(again.data(), full);
  EXPECT_LE(again.elements_with_stored_graph(), c.map->elements_with_stored_graph());
  EXPECT_GT(c.map->elements_with_stored_graph(), 0);
}

TEST(DerivedGraph, ArraysThatDoNotFollowFromTheRegionsAreKeptAsGiven) {
  const auto c = generators::subdivision_map(generators::bumpy_grid(2), 3, 0.1, 5);
  MapData<2> corrupt = c.map->data();
  // Element 1: two neighbours of its first node swapped (the cyclic order is now wrong, which
  // verify must still be able to see); element 3: its region neighbours' first entry changed.
  const Index n = corrupt.node_begin[1];
  ASSERT_GE(corrupt.neighbor_begin[n + 1] - corrupt.neighbor_begin[n], 2);
  std::swap(corrupt.neighbor[corrupt.neighbor_begin[n]], corrupt.neighbor[corrupt.neighbor_begin[n] + 1]);
  auto& rn = corrupt.region_neighbors[corrupt.region_begin[3]];
  rn[0] = rn[0] == invalid_index ? corrupt.region_begin[3] + 1 : invalid_index;
  const PlMap<2> map = rebuilt(*c.map, corrupt);
  EXPECT_EQ(map.elements_with_stored_graph(), 2);
  EXPECT_EQ(map.data(), corrupt);
  EXPECT_EQ(std::vector(map.region_neighbors().begin(), map.region_neighbors().end()), corrupt.region_neighbors);
}

TEST(DerivedGraph, CopiesAndConcurrentFirstUsesAgree) {
  const auto c = generators::subdivision_map(generators::bumpy_grid(3), 5, 0.1, 9);
  const PlMap<2> copy = *c.map;  // before anything was derived
  EXPECT_EQ(copy.derived_bytes(), 0u);
  std::vector<const MapData<2>*> seen(4);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < seen.size(); ++i)
    threads.emplace_back([&, i] {
      if (i % 2 == 0) copy.region_neighbors();
      seen[i] = &copy.data();
    });
  for (auto& t : threads) t.join();
  for (const auto* s : seen) EXPECT_EQ(s, &copy.data());
  EXPECT_EQ(copy.data(), c.map->data());
  MapData<2> released = PlMap<2>(copy).release_data();
  EXPECT_EQ(released, c.map->data());
}

}  // namespace
}  // namespace plmap
