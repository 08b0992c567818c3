// farther_overlapping_regions (construct/src/image_overlaps.hpp): of two regions whose images
// overlap on S2, the one farther from its image is named; maps whose images tile S2 name none.

#include "image_overlaps.hpp"
#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/core/face_removal.hpp>
#include <plmap/core/map_builder.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

using namespace plmap;
using namespace plmap::test;

namespace {

/// S1: two triangles, one above the other (z = 1 and z = 0); S2: one triangle at z = 2. The upper
/// triangle's corners are the preimages of S2's corners; the lower one's corners are ghost nodes
/// mapping into S2's triangle, so both S1 triangles map into it and their images overlap.
PlMap<2> stacked_triangles() {
  auto s1 = std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {0.2, 0.2, 0}, {0.7, 0.2, 0}, {0.2, 0.7, 0}},
      std::vector<ElementCorners<2>>{{0, 1, 2}, {3, 4, 5}});
  auto s2 = std::make_shared<const Surface<2>>(std::vector<WorldPoint<2>>{{0, 0, 2}, {1, 0, 2}, {0, 1, 2}},
                                               std::vector<ElementCorners<2>>{{0, 1, 2}});
  MapBuilder<2> b(s1, s2);
  for (Index v = 0; v < 3; ++v) b.add_vertex_preimage_at_vertex(v, v);
  b.add_ghost_node(3, {0, LocalPoint<2>(0.2, 0.2)});
  b.add_ghost_node(4, {0, LocalPoint<2>(0.7, 0.2)});
  b.add_ghost_node(5, {0, LocalPoint<2>(0.2, 0.7)});
  b.add_target_element(0);
  return std::move(b).finalize();
}

/// The same with curves: segments at y = 1 and y = 0 under one S2 segment at y = 2, which is
/// inserted as two pieces, one on each sheet (between ghost nodes mapping into it).
PlMap<1> stacked_segments() {
  auto s1 = std::make_shared<const Surface<1>>(std::vector<WorldPoint<1>>{{0.1, 1}, {0.9, 1}, {0.3, 0}, {0.6, 0}},
                                               std::vector<ElementCorners<1>>{{0, 1}, {2, 3}});
  auto s2 = std::make_shared<const Surface<1>>(std::vector<WorldPoint<1>>{{0, 2}, {1, 2}},
                                               std::vector<ElementCorners<1>>{{0, 1}});
  MapBuilder<1> b(s1, s2);
  const std::array<double, 4> at = {0.1, 0.9, 0.3, 0.6};
  for (Index v = 0; v < 4; ++v) b.add_ghost_node(v, {0, LocalPoint<1>(at[v])});
  const std::array<VertexCrossing, 2> upper = {VertexCrossing{0, 0.1}, VertexCrossing{1, 0.9}};
  const std::array<VertexCrossing, 2> lower = {VertexCrossing{2, 0.3}, VertexCrossing{3, 0.6}};
  b.add_edge_piece(0, upper, PieceStart::first_crossing, PieceEnd::last_crossing);
  b.add_edge_piece(0, lower, PieceStart::first_crossing, PieceEnd::last_crossing);
  return std::move(b).finalize();
}

}  // namespace

TEST(ImageOverlaps, TheFartherOfTwoStackedTrianglesIsNamed) {
  const PlMap<2> map = stacked_triangles();
  ASSERT_EQ(map.region_count(), 2);
  ASSERT_NE(verify_violations(map), "");  // the images overlap on S2: not a valid map
  const auto farther = projection::farther_overlapping_regions(map, image_measures(map));
  ASSERT_EQ(farther.size(), 1u);
  EXPECT_EQ(map.node_element(map.data().region_corners[farther[0]][0]), 1);  // the lower triangle
  const PlMap<2> kept = remove_faces(map, std::span<const Index>(farther));
  EXPECT_EQ(kept.region_count(), 1);
  EXPECT_EQ(verify_violations(kept), "");
  EXPECT_TRUE(projection::farther_overlapping_regions(kept, image_measures(kept)).empty());
}

TEST(ImageOverlaps, TheFartherOfTwoStackedSegmentsIsNamed) {
  const PlMap<1> map = stacked_segments();
  ASSERT_EQ(map.region_count(), 2);
  ASSERT_NE(verify_violations(map), "");
  const auto farther = projection::farther_overlapping_regions(map, image_measures(map));
  ASSERT_EQ(farther.size(), 1u);
  EXPECT_EQ(map.node_element(map.data().region_corners[farther[0]][0]), 1);
  EXPECT_EQ(verify_violations(remove_faces(map, std::span<const Index>(farther))), "");
}

TEST(ImageOverlaps, TilingImagesNameNothing) {
  // A projection between two planes: the images tile S2 where S1 lies under it.
  const auto s1 = grid(12, 12, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.15);
  const auto s2 = grid(17, 17, -0.2, 1.2, -0.2, 1.2, 0.3, true, 0.15);
  const auto r = project<2>(s1, s2, {.keep_nearer_sheet = false});
  ASSERT_GT(r.map.region_count(), 100);
  EXPECT_TRUE(projection::farther_overlapping_regions(r.map, image_measures(r.map)).empty());
  EXPECT_EQ(r.report.occluded_faces, 0);
}

TEST(ImageOverlaps, OneConnectedSheetReachingOverItselfOnAPartlyCoveredElementIsFound) {
  // Three S1 triangles around vertex c, edge-connected, spanning 270 degrees; their corners are
  // ghost nodes whose images on one large S2 triangle turn by 150 degrees per triangle, so the
  // first and the last image overlap (each is positively oriented, no fold). The images add up
  // to far less than the S2 triangle and come from one connected sheet: the overlap is found
  // only by comparing the images on S2 elements that are partly covered (seed 5 of
  // ProjectProperties.OffsetHeightFieldsWithAveragedNormals has this on a curved S1).
  auto s1 = std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}},
      std::vector<ElementCorners<2>>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}});
  auto s2 = std::make_shared<const Surface<2>>(std::vector<WorldPoint<2>>{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}},
                                               std::vector<ElementCorners<2>>{{0, 1, 2}});
  const LocalPoint<2> c(0.3, 0.3);
  const auto at = [&](double degrees, double radius) {
    const double a = degrees * std::numbers::pi / 180.0;
    return LocalPoint<2>(c + radius * LocalPoint<2>(std::cos(a), std::sin(a)));
  };
  MapBuilder<2> b(s1, s2);
  b.add_ghost_node(0, {0, c});
  b.add_ghost_node(1, {0, at(0, 0.1)});
  b.add_ghost_node(2, {0, at(150, 0.1)});
  b.add_ghost_node(3, {0, at(300, 0.1)});
  b.add_ghost_node(4, {0, at(450, 0.08)});
  for (Index e = 0; e < 3; ++e) b.add_edge_outside_domain(e);
  const PlMap<2> map = std::move(b).finalize();
  ASSERT_EQ(map.region_count(), 3);
  ASSERT_NE(verify_violations(map), "");  // the first and the last image overlap
  const auto farther = projection::farther_overlapping_regions(map, image_measures(map));
  ASSERT_EQ(farther.size(), 1u);
  const Index element = map.node_element(map.data().region_corners[farther[0]][0]);
  EXPECT_TRUE(element == 0 || element == 2) << element;
  EXPECT_EQ(verify_violations(remove_faces(map, std::span<const Index>(farther))), "");
}

/// S1: a plane under a narrower plane (two sheets, 10,400 triangles: more than one piece of S1
/// elements per thread); the lower sheet's elements come first.
std::shared_ptr<const Surface<2>> two_stacked_sheets(Index& lower_elements) {
  const auto lower = grid(60, 60, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.15);
  const auto upper = grid(40, 40, 0.3, 0.7, 0.0, 1.0, 0.4, false, 0.15);
  lower_elements = lower->element_count();
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  for (const auto* s : {lower.get(), upper.get()}) {
    const auto base = static_cast<Index>(v.size());
    for (Index i = 0; i < s->vertex_count(); ++i) v.push_back(s->vertex(i));
    for (Index t = 0; t < s->element_count(); ++t) {
      ElementCorners<2> c = s->element(t);
      for (Index& x : c) x += base;
      e.push_back(c);
    }
  }
  return std::make_shared<const Surface<2>>(std::move(v), std::move(e));
}

TEST(ImageOverlaps, TheThreadCountDoesNotChangeWhatIsNamed) {
  // S1: two stacked sheets, S2: a plane above both (5,000 triangles: several chunks of S2
  // elements). Without the sheet selection both sheets map onto S2 where they overlap.
  Index lower_elements = 0;
  const auto s1 = two_stacked_sheets(lower_elements);
  const auto s2 = grid(50, 50, -0.1, 1.1, -0.1, 1.1, 1.0, true, 0.15);
  const auto r = project<2>(s1, s2, {.keep_nearer_sheet = false});
  const ImageMeasures images = image_measures(r.map);
  const auto one = projection::farther_overlapping_regions(r.map, images, {}, 1);
  ASSERT_GT(one.size(), 100u);
  EXPECT_EQ(projection::farther_overlapping_regions(r.map, images, {}, 2), one);
  EXPECT_EQ(projection::farther_overlapping_regions(r.map, images, {}, 3), one);
  // the lower sheet is the farther one: every region named lies on it
  for (const Index region : one) EXPECT_LT(r.map.node_element(r.map.data().region_corners[region][0]), lower_elements);
}

TEST(ImageOverlaps, TheSheetSelectionReportsTheMeasuresOfTheMapItLeaves) {
  // The sheet selection brings the image measures up to the map without measuring it again: S1's
  // side to the last bit, S2's side to rounding, the same for every thread count.
  Index lower_elements = 0;
  const auto s1 = two_stacked_sheets(lower_elements);
  const auto s2 = grid(50, 50, -0.1, 1.1, -0.1, 1.1, 1.0, true, 0.15);
  ProjectionOptions options;
  options.threads = 1;
  const auto one = project<2>(s1, s2, options);
  ASSERT_GT(one.report.occluded_regions, 100);
  const ImageMeasures measured = image_measures(one.map);
  EXPECT_EQ(one.measures.covered_domain, measured.covered.domain);
  EXPECT_NEAR(one.measures.covered_target, measured.covered.target, 1e-12 * measured.covered.target);
  // the images cover the lower sheet's footprint once (S2 has measure 1.44); what goes beside the
  // upper sheet's sides, where the lower sheet's regions are only partly hidden, is a thin strip
  EXPECT_LE(one.measures.covered_target, 1.0 + 1e-9);
  EXPECT_GT(one.measures.covered_target, 0.97);
  options.threads = 2;
  const auto two = project<2>(s1, s2, options);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(two.measures.covered_target), std::bit_cast<std::uint64_t>(one.measures.covered_target));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(two.measures.covered_domain), std::bit_cast<std::uint64_t>(one.measures.covered_domain));
}
