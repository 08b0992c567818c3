// FreeNodeFans (construct/src/free_node_fans.hpp), read by the element smoothing instead of the
// map's derived graph, must give exactly PlMap::neighbors() for every interior node whose
// regions close a fan, and nothing for the others (the smoothing skips those as open stars).

#include "free_node_fans.hpp"
#include "simplified_spheres.hpp"

#include <plmap/construct/simplify.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>
#include <plmap/verify/generators/random_maps.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <vector>

namespace plmap::smoothing {
namespace {

/// Checks every interior node of `map`; returns how many had a closed fan.
int check_fans_against_neighbors(const PlMap<2>& map) {
  RC_PRE(map.elements_with_stored_graph() == 0);
  const MapData<2>& m = map.data();
  FreeNodeFans fans;
  std::vector<char> free;
  int closed = 0;
  for (Index t = 0; t < map.domain().element_count(); ++t) {
    const Index nb = m.node_begin[t], ne = m.node_begin[t + 1];
    free.assign(static_cast<std::size_t>(ne - nb), 0);
    std::vector<int> incidence(static_cast<std::size_t>(ne - nb), 0);
    for (Index n = nb; n < ne; ++n) free[static_cast<std::size_t>(n - nb)] = m.node_type[n] == NodeType::interior;
    for (Index r = m.region_begin[t]; r < m.region_begin[t + 1]; ++r)
      for (Index c : m.region_corners[r]) ++incidence[static_cast<std::size_t>(c - nb)];
    fans.collect(m, t, free);
    for (Index n = nb; n < ne; ++n) {
      if (!free[static_cast<std::size_t>(n - nb)]) continue;
      const std::span<const Index> ring = fans.ring(n);
      const std::span<const Index> derived = map.neighbors(n);
      if (static_cast<int>(derived.size()) == incidence[static_cast<std::size_t>(n - nb)]) {
        RC_ASSERT(std::vector<Index>(ring.begin(), ring.end()) == std::vector<Index>(derived.begin(), derived.end()));
        ++closed;
      } else {
        RC_ASSERT(ring.empty());
      }
    }
  }
  return closed;
}

RC_GTEST_PROP(FreeNodeFans, AgreeWithTheDerivedNeighboursOnRefinementMaps, ()) {
  const auto c = *generators::refinement_maps<2>();
  RC_LOG() << c.description << "\n";
  RC_CLASSIFY(check_fans_against_neighbors(*c.map) > 0, "closed fans");
}

RC_GTEST_PROP(FreeNodeFans, AgreeWithTheDerivedNeighboursOnSimplifiedSpheres, ()) {
  const int subdivisions = *rc::gen::inRange(1, 3);
  const int jitter_percent = *rc::gen::inRange(0, 25);
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const int percent = *rc::gen::inRange(10, 60);
  const SimplifyResult simplified = simplify_test::simplified_sphere(subdivisions, jitter_percent / 100.0, seed, percent);
  RC_ASSERT(check_fans_against_neighbors(simplified.map) > 0);
}

TEST(FreeNodeFans, AnOpenFanHasNoRing) {
  // one element, a free node 3 with regions (3, 0, 1) and (3, 1, 2) only: the side 3-2 ... 3-0
  // has no region, so the fan does not close
  MapData<2> m;
  m.node_begin = {0, 4};
  m.region_begin = {0, 2};
  m.region_corners = {{3, 0, 1}, {3, 1, 2}};
  FreeNodeFans fans;
  const std::vector<char> free = {0, 0, 0, 1};
  fans.collect(m, 0, free);
  EXPECT_TRUE(fans.ring(3).empty());
  m.region_corners.push_back({3, 2, 0});  // now it closes: from the smallest neighbour on
  m.region_begin = {0, 3};
  fans.collect(m, 0, free);
  const std::span<const Index> ring = fans.ring(3);
  EXPECT_EQ(std::vector<Index>(ring.begin(), ring.end()), (std::vector<Index>{0, 1, 2}));
}

}  // namespace
}  // namespace plmap::smoothing
