// A projection hands its map over in the stored form and derives nothing on the way: the graph
// arrays of the elements its regions tile are derived only when something walks the graph
// (docs/data-model.md, "What is stored and what is derived"). A step of finalize that reads the
// map through data() instead of stored() derives the whole graph, serially, inside the timed
// projection (it once cost 0.1 s of the 200k-triangle planes' 2.5 s).

#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>

#include <gtest/gtest.h>

namespace plmap {
namespace {

TEST(ProjectionStoredForm, TheProjectedMapHasDerivedNothing) {
  // a shifted, finer target: elements partly outside D store their graph, the rest derive it
  const auto s1 = test::grid(20, 20, 0, 1, 0, 1, 0.0);
  const auto s2 = test::grid(25, 25, 0.3, 1.3, 0.2, 1.2, 0.1);
  const PlMap<2> map = project<2>(s1, s2).map;
  EXPECT_EQ(map.derived_bytes(), 0u);
  EXPECT_GT(map.elements_with_stored_graph(), 0);
  EXPECT_LT(map.elements_with_stored_graph(), map.domain().element_count());
  // and what is derived later is what a map handed the full arrays keeps
  const MapData<2> full = map.data();
  EXPECT_GT(map.derived_bytes(), 0u);
  const PlMap<2> again(map.domain_ptr(), map.target_ptr(), full);
  EXPECT_EQ(again.data(), full);
}

}  // namespace
}  // namespace plmap
