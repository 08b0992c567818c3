// The snapping rule (core/snapping.hpp), which MapBuilder and project() share.
#include <plmap/core/map_builder.hpp>
#include <plmap/core/snapping.hpp>

#include <gtest/gtest.h>

#include <utility>

using namespace plmap;

TEST(Snapping, SmallAndSlightlyNegativeWeightsBecomeZero) {
  const double tol = 1e-10;
  const Barycentric<2> edge = snap_barycentric<2>(Barycentric<2>(0.25, 0.75 - 5e-11, 5e-11), tol);
  EXPECT_EQ(edge(2), 0.0);
  EXPECT_DOUBLE_EQ(edge(0) + edge(1), 1.0);
  const Barycentric<2> corner = snap_barycentric<2>(Barycentric<2>(1.0 + 3e-11, -4e-11, 1e-11), tol);
  EXPECT_EQ(corner, Barycentric<2>(1.0, 0.0, 0.0));
  const Barycentric<2> inside(0.2, 0.3, 0.5);
  EXPECT_EQ(snap_barycentric<2>(inside, tol), inside);
  // just above the tolerance: kept
  const Barycentric<1> kept = snap_barycentric<1>(Barycentric<1>(1.0 - 2e-10, 2e-10), tol);
  EXPECT_GT(kept(1), 0.0);
}

TEST(Snapping, EdgeParametersNearTheEndsAreTheEndVertices) {
  const double tol = 1e-10;
  EXPECT_EQ(snap_edge_parameter(0.0, tol), EdgeSnap::first_vertex);
  EXPECT_EQ(snap_edge_parameter(-5e-11, tol), EdgeSnap::first_vertex);
  EXPECT_EQ(snap_edge_parameter(1e-10, tol), EdgeSnap::first_vertex);
  EXPECT_EQ(snap_edge_parameter(2e-10, tol), EdgeSnap::inside);
  EXPECT_EQ(snap_edge_parameter(0.5, tol), EdgeSnap::inside);
  EXPECT_EQ(snap_edge_parameter(1.0 - 5e-11, tol), EdgeSnap::second_vertex);
}

TEST(Snapping, TheBuilderUsesTheSameRule) {
  // A vertex preimage 5e-11 from an edge of the element becomes a touching node, one 2e-10 away
  // an interior node: the builder snaps exactly as snap_barycentric does.
  auto s1 = std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}},
      std::vector<std::array<Index, 3>>{{0, 1, 2}, {1, 3, 2}});
  auto s2 = std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0.2, 0.0, 0}, {0.6, 0.3, 0}, {0.3, 0.6, 0}},
      std::vector<std::array<Index, 3>>{{0, 1, 2}});
  for (const auto& [y, touching_expected] : {std::pair{5e-11, 1}, std::pair{2e-10, 0}}) {
    MapBuilder<2> b(s1, s2);
    b.add_vertex_preimage(0, {0, LocalPoint<2>(0.2, y)});
    b.add_vertex_preimage(1, {0, LocalPoint<2>(0.6, 0.3)});
    b.add_vertex_preimage(2, {0, LocalPoint<2>(0.3, 0.6)});
    b.add_target_element(0);
    const PlMap<2> map = std::move(b).finalize();
    int touching = 0;
    for (NodeType t : map.data().node_type) touching += t == NodeType::touching;
    EXPECT_EQ(touching, touching_expected) << "y = " << y;
    // and that is what the shared rule says of the same point
    const bool snapped = snap_barycentric<2>(barycentric_from_local<2>(LocalPoint<2>(0.2, y)), 1e-10)(2) == 0.0;
    EXPECT_EQ(snapped, touching_expected == 1) << "y = " << y;
  }
}
