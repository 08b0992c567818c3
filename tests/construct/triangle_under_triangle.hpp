#pragma once
// One S1 triangle under one S2 triangle two units above it, Xi the vertical lift: the smallest
// projection-like map, for the tests of the checks that judge regions by their rays.

#include <plmap/core/map_builder.hpp>

#include <memory>
#include <vector>

namespace plmap::test {

inline PlMap<2> triangle_under_triangle() {
  auto s1 = std::make_shared<const Surface<2>>(std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                               std::vector<ElementCorners<2>>{{0, 1, 2}});
  auto s2 = std::make_shared<const Surface<2>>(std::vector<WorldPoint<2>>{{0, 0, 2}, {1, 0, 2}, {0, 1, 2}},
                                               std::vector<ElementCorners<2>>{{0, 1, 2}});
  MapBuilder<2> b(s1, s2);
  for (Index v = 0; v < 3; ++v) b.add_vertex_preimage_at_vertex(v, v);
  b.add_target_element(0);
  return std::move(b).finalize();
}

}  // namespace plmap::test
