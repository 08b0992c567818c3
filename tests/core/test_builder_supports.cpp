// White-box test of the builder's image supports (core/src/builder_nodes.hpp): a support keeps
// its S2 vertices as corner numbers of its element, so the vertices it gives back, the local
// coordinates it hands to the stored form (on its own element or on any other element that
// contains it) and the weight it leaves out must be exactly those of the vertices and weights
// it was given: the map written depends on them to the last bit.

#include "builder_nodes.hpp"
#include "finalize_region_maps.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/surface.hpp>

#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <vector>

using namespace plmap;
using namespace plmap::detail;

namespace {

/// Two triangles sharing edge (1, 2), their corners in different orders, so that a shared vertex
/// has different corner numbers on the two elements.
Surface<2> two_triangles() {
  std::vector<WorldPoint<2>> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.25}};
  std::vector<ElementCorners<2>> t = {{0, 1, 2}, {2, 1, 3}};
  return Surface<2>(v, t);
}

/// The support with the given corners of element t and weights, entered as the builder enters
/// them (in the order given).
Support<2> support_on(Index t, const std::vector<int>& corners, const std::vector<double>& weights) {
  Support<2> s;
  s.element = t;
  for (std::size_t i = 0; i < corners.size(); ++i) s.add(corners[i], weights[i]);
  return s;
}

}  // namespace

TEST(BuilderSupports, NodesStayCompact) {
  EXPECT_LE(sizeof(BuilderNode<2>), 64u);
  EXPECT_LE(sizeof(BuilderNode<1>), 48u);
}

TEST(BuilderSupports, GiveBackTheirVerticesAndWeightsExactly) {
  const Surface<2> s2 = two_triangles();
  // weights that do not survive a round trip through arithmetic (1 - w is not exact for them)
  const double a = 0.1, b = 0.7000000000000001, c = 1.0 / 3.0;
  for (Index t = 0; t < 2; ++t) {
    const std::vector<std::vector<int>> corner_sets = {{0}, {1}, {2}, {0, 1}, {2, 0}, {1, 2}, {0, 1, 2}, {2, 1, 0}};
    for (const auto& corners : corner_sets) {
      const std::vector<double> weights = {a, b, c};
      const Support<2> s = support_on(t, corners, weights);
      ASSERT_EQ(s.count, static_cast<int>(corners.size()));
      LocalPoint<2> expected = LocalPoint<2>::Zero();
      double omitted = 0.0;
      for (std::size_t i = 0; i < corners.size(); ++i) {
        EXPECT_EQ(s.corner(static_cast<int>(i)), corners[i]);
        EXPECT_EQ(s.vertex(s2, static_cast<int>(i)), s2.element(t)[corners[i]]);
        EXPECT_EQ(s.weight[i], weights[i]);  // bit for bit
        if (corners[i] > 0) expected(corners[i] - 1) = weights[i];
        else omitted = weights[i];
      }
      EXPECT_TRUE(support_in_element<2>(s2, s, t));
      const LocalPoint<2> y = support_local<2>(s2, s, t);
      EXPECT_EQ(y(0), expected(0));
      EXPECT_EQ(y(1), expected(1));
      EXPECT_EQ(omitted_image_weight(s), omitted);
    }
  }
}

TEST(BuilderSupports, MoveExactlyOntoAnotherElementThatContainsThem) {
  const Surface<2> s2 = two_triangles();
  // the point 0.3 (vertex 1) + 0.7 (vertex 2) on the shared edge, entered on element 0, where
  // vertices 1 and 2 are corners 1 and 2; on element 1 = (2, 1, 3) they are corners 1 and 0
  const Support<2> s = support_on(0, {1, 2}, {0.3, 0.7});
  EXPECT_TRUE(support_in_element<2>(s2, s, 1));
  const LocalPoint<2> y = support_local<2>(s2, s, 1);
  EXPECT_EQ(y(0), 0.3);  // vertex 1 is corner 1 of element 1
  EXPECT_EQ(y(1), 0.0);  // vertex 3 carries no weight
  // a support with vertex 0 (not a corner of element 1) is not in element 1
  EXPECT_FALSE(support_in_element<2>(s2, support_on(0, {0, 1}, {0.5, 0.5}), 1));
  EXPECT_THROW(support_local<2>(s2, support_on(0, {0, 1}, {0.5, 0.5}), 1), BuilderError);
}

// The assembly keeps a node's omitted weight only where 1 minus its stored two does not give it
// back bit for bit (finalize_region_maps.hpp): there it keeps the support's own.
TEST(BuilderSupports, KeepTheOmittedWeightOnlyWhereTheStoredOnesDoNotGiveItBack) {
  const Surface<2> s2 = two_triangles();
  auto kept = [&](const Support<2>& s) { return omitted_weight_to_keep(s, support_local<2>(s2, s, s.element)); };
  EXPECT_FALSE(kept(support_on(0, {0, 1}, {0.75, 0.25})).has_value());  // 1 - 0.25 is 0.75 exactly
  EXPECT_FALSE(kept(support_on(0, {1, 2}, {0.3, 0.7})).has_value());    // no corner 0: +0.0 = 1 - (0.3 + 0.7)
  EXPECT_FALSE(kept(support_on(0, {1}, {1.0})).has_value());             // at a vertex: +0.0
  // 1 - 0.7 is 0.30000000000000004, not 0.3
  const std::optional<double> edge = kept(support_on(0, {0, 2}, {0.3, 0.7}));
  ASSERT_TRUE(edge.has_value());
  EXPECT_EQ(*edge, 0.3);
  // three weights that do not sum to 1 exactly
  const std::optional<double> inside = kept(support_on(1, {2, 0, 1}, {0.1, 0.7000000000000001, 1.0 / 3.0}));
  ASSERT_TRUE(inside.has_value());
  EXPECT_EQ(*inside, 0.7000000000000001);
}
